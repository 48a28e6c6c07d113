"""Data files shipped with homebot: worlds, knowledge bases, dialogue models, domains."""
