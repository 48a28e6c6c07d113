"""The seeds' demonstrations and the stories they tell, run in homes that ``homebot.app``
builds."""

__all__: list[str] = []
