"""How ownctl's commands look in ``--help``: plain text, like a Unix tool's manual.

Every command group is a :class:`Group` and every command an :class:`OwnctlCommand`, so help is
rendered by the plain formatter (square brackets in help texts are text, not markup), arguments
and option values show readable metavars (``OBJ``, ``AGENT``, ``P``, ``FILE``) instead of type
names, and the usage line reads ``ownctl claim [OPTIONS] OBJ AGENT``. Kept free of heavy imports:
``ownctl --help`` loads this module.
"""

from __future__ import annotations

from typing import Any

import typer
from typer.core import TyperCommand


def metavar(param: Any) -> str:
    """The name shown for an argument or an option's value: its metavar, else its name in capitals."""
    return param.metavar or (param.name or "value").upper()


class OwnctlCommand(TyperCommand):
    """A command whose help shows metavars, never type names, and no markup."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        for param in self.params:
            if param.param_type_name == "argument" or not getattr(param, "is_flag", False):
                param.metavar = metavar(param)

    def collect_usage_pieces(self, ctx: Any) -> list[str]:
        """``[OPTIONS] OBJ AGENT [WORDS]...``: required arguments bare, optional ones in brackets."""
        pieces = [self.options_metavar] if self.options_metavar else []
        for param in self.get_params(ctx):
            if param.param_type_name == "argument":
                name = metavar(param) if param.required else f"[{metavar(param)}]"
                pieces.append(name + ("..." if param.nargs != 1 else ""))
        return pieces

    def format_options(self, ctx: Any, formatter: Any) -> None:
        """An Arguments section (metavar, help) and an Options section (flags, metavar, help)."""
        arguments = [(metavar(p), getattr(p, "help", None) or "") for p in self.get_params(ctx)
                     if p.param_type_name == "argument" and not getattr(p, "hidden", False)]
        options = [record for p in self.get_params(ctx)
                   if p.param_type_name == "option" and (record := p.get_help_record(ctx)) is not None]
        if arguments:
            with formatter.section("Arguments"):
                formatter.write_dl(arguments)
        if options:
            with formatter.section("Options"):
                formatter.write_dl(options)


class Group(typer.Typer):
    """A command group with plain help whose commands are :class:`OwnctlCommand`.

    A group run without a command is a usage error naming its commands (exit 2), not a help page:
    ``--help`` shows the help.
    """

    def __init__(self, *, help: str, **kwargs: Any) -> None:
        kwargs.setdefault("no_args_is_help", False)
        super().__init__(help=help, rich_markup_mode=None, add_completion=False,
                         pretty_exceptions_enable=False, **kwargs)

    def command(self, name: str | None = None, *, cls: type[TyperCommand] | None = None,
                **kwargs: Any) -> Any:
        """Register a command (an :class:`OwnctlCommand` unless ``cls`` says otherwise)."""
        return super().command(name, cls=cls or OwnctlCommand, **kwargs)
