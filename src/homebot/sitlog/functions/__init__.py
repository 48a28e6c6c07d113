"""User functions of the shipped dialogue models (named under ``functions:`` in their YAML)."""

__all__: list[str] = []
