"""homebot: a cognitive software stack for domestic service robots."""

from homebot.errors import HomebotError

__all__ = ["HomebotError", "__version__"]

__version__ = "0.1.0"
