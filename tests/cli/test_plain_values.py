"""The plain-value conversion of command parameters gives exactly what typer's own conversion gives:
the same value (bit for bit) or the same error, for values of the parameter's type and for text."""

from __future__ import annotations

import math
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer._coercion import build_runtime_param

from ownctl.cli.help import PlainValue
from ownctl.cli.main import command


def _param(cmd: str, name: str) -> tuple[Any, Any]:
    """A parameter of ``ownctl CMD`` and a context of that command."""
    click_cmd = command().commands[cmd]
    param = next(p for p in click_cmd.params if p.name == name)
    ctx = click_cmd.context_class(click_cmd, info_name=cmd)
    return param, ctx


def _outcome(conversion: Any, value: Any, param: Any, ctx: Any) -> tuple[str, Any]:
    try:
        out = conversion._coerce_value(value, param=param, ctx=ctx)
    except Exception as exc:  # the same kind of error with the same message
        return type(exc).__name__, str(exc)
    return type(out).__name__, repr(out) if isinstance(out, float) and math.isnan(out) else out


# a float, texts, a flag, and an int (whose conversion turns True into 1: type, not isinstance)
CASES = [("claim", "p"), ("claim", "obj"), ("claim", "negated"), ("check", "action"), ("log", "limit")]


VALUES = st.one_of(st.text(max_size=12), st.floats(allow_nan=True), st.integers(-10**6, 10**6), st.booleans(),
                   st.sampled_from(["0.75", "1e-3", "nan", "inf", "-0", "12", " 3 ", "x"]))


@pytest.mark.parametrize(("cmd", "name"), CASES)
@settings(max_examples=60, deadline=None)
@given(value=VALUES)
def test_plain_values_convert_as_typer_does(cmd: str, name: str, value: Any) -> None:
    param, ctx = _param(cmd, name)
    descriptor = param.type_descriptor
    plain = PlainValue(descriptor.parameter_info, descriptor.annotation)
    typers = build_runtime_param(descriptor)
    ours = _outcome(plain, value, param, ctx)
    assert ours == _outcome(typers, value, param, ctx)
    if ours[0] != "BadParameter":
        assert type(plain._coerce_value(value, param=param, ctx=ctx)) is type(
            typers._coerce_value(value, param=param, ctx=ctx))


def test_check_and_claim_parameters_are_plain() -> None:
    for cmd in ("check", "claim"):
        click_cmd = command().commands[cmd]
        kinds = {p.name: type(p._runtime_param).__name__ for p in click_cmd.params}
        assert set(kinds.values()) == {"PlainValue"}, kinds
