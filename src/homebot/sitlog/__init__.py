"""SitLog: dialogue models of situations and arcs, interpreted over the skills (Golem-III §4)."""

from homebot.sitlog.diagram import dot_diagram
from homebot.sitlog.history import History, Transition, render_globals, render_history
from homebot.sitlog.interpreter import DialogueTrace, Environment, Interpreter, RunStopped
from homebot.sitlog.loading import load_program, load_program_text, shipped_dialogue_path
from homebot.sitlog.model import Arc, DialogueModel, Program, Situation, UserFunction
from homebot.sitlog.perception import Body, Perception, RecordingBody, ScriptedPerception
from homebot.sitlog.terms import Struct, Term, Text, Var, format_term, parse_term

__all__ = [
    "Arc",
    "Body",
    "DialogueModel",
    "DialogueTrace",
    "Environment",
    "History",
    "Interpreter",
    "Perception",
    "Program",
    "RecordingBody",
    "RunStopped",
    "ScriptedPerception",
    "Situation",
    "Struct",
    "Term",
    "Text",
    "Transition",
    "UserFunction",
    "Var",
    "dot_diagram",
    "format_term",
    "load_program",
    "load_program_text",
    "parse_term",
    "render_globals",
    "render_history",
    "shipped_dialogue_path",
]
