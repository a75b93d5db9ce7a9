"""How ownctl's commands look in ``--help``: plain text, like a Unix tool's manual.

Every command group is a :class:`Group` and every command an :class:`OwnctlCommand`, so help is
rendered by the plain formatter (square brackets in help texts are text, not markup), arguments
and option values show readable metavars (``OBJ``, ``AGENT``, ``P``, ``FILE``) instead of type
names, and the usage line reads ``ownctl claim [OPTIONS] OBJ AGENT``. Kept free of heavy imports:
``ownctl --help`` loads this module.

Parameters convert their values as typer does, through pydantic, except where that cannot change
the value (:func:`plain_values`): a text argument, a flag, or a number option left at its default. So
``ownctl check ACTION OBJ`` and ``ownctl claim OBJ AGENT`` never import pydantic (about a third of
their start-up otherwise); ``--p 0.75`` still converts, and fails, exactly as typer's own.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import typer
from typer.core import TyperCommand

try:  # typer's conversion of one parameter's value (typer 0.29); without it, typer's own is used
    from typer._coercion import RuntimeParam, build_runtime_param
except ImportError:  # pragma: no cover - another typer
    RuntimeParam = None  # type: ignore[assignment,misc]

PLAIN_TYPES = (str, bool, int, float)

if RuntimeParam is not None:

    @dataclass(frozen=True)
    class PlainValue(RuntimeParam):
        """A value already of the parameter's type is kept as it is (what typer's conversion returns
        for it); any other goes through typer's conversion, built when first needed."""

        def _coerce_value(self, value: Any, param: Any, ctx: Any) -> Any:
            if type(value) is self.annotation:
                return value
            full = param.__dict__.get("_ownctl_conversion")
            if full is None:
                full = param.__dict__["_ownctl_conversion"] = build_runtime_param(param.type_descriptor)
            return full._coerce_value(value, param=param, ctx=ctx)


def _plain(descriptor: Any) -> bool:
    """Whether typer would convert a value of ``descriptor``'s own type to itself: a bare text or
    number parameter, without a parser, choices, file, or bounds."""
    info = descriptor.parameter_info
    return (descriptor.annotation in PLAIN_TYPES and getattr(info, "parser", None) is None
            and getattr(info, "click_type", None) is None and descriptor.file_annotation is None
            and getattr(info, "min", None) is None and getattr(info, "max", None) is None
            and not descriptor.is_choice)


def plain_values(params: Iterable[Any]) -> None:
    """Give every plain parameter of a command (see :func:`_plain`) the :class:`PlainValue` conversion."""
    if RuntimeParam is None:
        return
    for param in params:
        descriptor = getattr(param, "type_descriptor", None)
        if descriptor is not None and getattr(param, "_runtime_param", False) is None and _plain(descriptor):
            param._runtime_param = PlainValue(descriptor.parameter_info, descriptor.annotation)


def metavar(param: Any) -> str:
    """The name shown for an argument or an option's value: its metavar, else its name in capitals."""
    return param.metavar or (param.name or "value").upper()


class OwnctlCommand(TyperCommand):
    """A command whose help shows metavars, never type names, and no markup."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        plain_values(self.params)
        for param in self.params:
            if param.param_type_name == "argument" or not getattr(param, "is_flag", False):
                param.metavar = metavar(param)

    def get_help_option(self, ctx: Any) -> Any:
        """``--help``, a flag that needs no conversion either."""
        option = super().get_help_option(ctx)
        plain_values([] if option is None else [option])
        return option

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
