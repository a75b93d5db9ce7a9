"""The robot's mind: claims, priors, posteriors, permissions and rules, and the instructions that
change them (:class:`Mind`; see ``docs/architecture.md``)."""

from ownctl.mind.core import (
    KEEP,
    PERMISSION_CUT,
    RESETS,
    SWITCHES,
    ClaimInfo,
    Given,
    Mind,
    NormResult,
    RuleInfo,
    Switches,
    WholeMindNeeded,
)

__all__ = ["KEEP", "PERMISSION_CUT", "RESETS", "SWITCHES", "ClaimInfo", "Given", "Mind", "NormResult",
           "RuleInfo", "Switches", "WholeMindNeeded"]
