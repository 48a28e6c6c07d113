"""Python equivalents (written for homebot) of the Java functions JSHOP2's freecell and test
examples call; used with the distribution's example files, which homebot does not ship."""

from typing import Any


def checknull(value: Any, otherwise: Any) -> Any:
    """``otherwise`` when ``value`` is nil (the empty list), else 0."""
    return otherwise if value == () else 0


def myfunc(*numbers: float) -> float:
    """The sum of the numbers."""
    return float(sum(numbers))


def mycomparator(a: Any, b: Any) -> int:
    """Odd numbers before even ones (as the test example's comparator)."""
    if int(a) & 1:
        return -1
    if int(b) & 1:
        return 1
    return 0
