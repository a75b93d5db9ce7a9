"""The natural-language front end: a grammar-based semantic parser (no network, no model).

``understand("No Baxter, that's mine!", Context(speaker="casey", about="wallet", action="trash",
agents=..., objects=...))`` returns an :class:`Understanding` whose instructions are the paper's
decomposition of a reprimand: ``skip wallet``, ``claim wallet casey``, ``forbid trash on wallet``,
``forbid trash if ownedBy casey``. Pure: no I/O; it imports only ``ownctl.logic`` and
``ownctl.errors``.
"""

from ownctl.language.context import Context, MissingContext, NotUnderstood, Understanding
from ownctl.language.instructions import (
    OBJECT_ACTIONS,
    TASKS,
    AskActions,
    AskOwned,
    AskOwner,
    AskPermitted,
    AskWhy,
    Claim,
    Instruction,
    Introduce,
    NormInstruction,
    Permission,
    Request,
    RunTask,
    Skip,
    teaching_order,
)
from ownctl.language.normalize import normalize
from ownctl.language.understand import RULES, understand

__all__ = [
    "teaching_order",
    "RULES",
    "OBJECT_ACTIONS",
    "TASKS",
    "AskActions",
    "AskOwned",
    "AskOwner",
    "AskPermitted",
    "AskWhy",
    "Claim",
    "Context",
    "Instruction",
    "Introduce",
    "MissingContext",
    "NormInstruction",
    "NotUnderstood",
    "Permission",
    "Request",
    "RunTask",
    "Skip",
    "Understanding",
    "normalize",
    "understand",
]
