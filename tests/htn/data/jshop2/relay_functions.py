"""The relay fixture's own function (a JSHOP2 domain would take it as a Java class)."""


def ticket(number: float) -> float:
    """The ticket of a parcel: its number times ten, plus one."""
    return number * 10 + 1
