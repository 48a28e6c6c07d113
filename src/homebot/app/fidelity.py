"""The two fidelities a run's robot can be simulated in, and what the embodied one needs."""

from __future__ import annotations

import importlib.util
from enum import StrEnum

from homebot.errors import HomebotError

__all__ = ["Fidelity", "require_embodied"]


class Fidelity(StrEnum):
    """How the robot under the skills is simulated."""

    SYMBOLIC = "symbolic"  #: percepts are seeded dice over the truth; motion jumps along paths
    EMBODIED = "embodied"  #: a body with a laser, localisation and reactive navigation


def require_embodied() -> None:
    """Raise a clear error when the ``embodied`` extra is not installed."""
    if importlib.util.find_spec("cv2") is None:
        raise HomebotError("--fidelity embodied needs the 'embodied' extra: "
                           "pip install 'homebot[embodied]'")
