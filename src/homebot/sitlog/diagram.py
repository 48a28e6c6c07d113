"""The diagram of a SitLog program (§4.3, Figure 3) as Graphviz dot text; a pure function."""

from __future__ import annotations

from homebot.sitlog.model import FINAL, RECURSIVE, DialogueModel, Program, Situation, functor_of
from homebot.sitlog.terms import Struct, Term, deref, format_term

__all__ = ["dot_diagram"]


def dot_diagram(program: Program) -> str:
    """Dialogue models as dotted clusters, situations as circles (id and type), arcs as α:β.

    A next situation given by a function is drawn as a bold dot labelled with the
    function, with an arrow to each value the function declares (``values``
    attribute of the Python function) or, without one, to every situation of its
    model. A recursive situation has a bold arrow (the pipe) to the initial situation
    of its embedded model; the main model's bold arrow out is ``out_arg``.
    """
    lines = ["digraph sitlog {", "  compound=true;", "  node [fontname=\"Helvetica\"];",
             "  edge [fontname=\"Helvetica\", fontsize=10];"]
    for index, model in enumerate(program.models.values()):
        lines.extend(_cluster(program, model, index))
    main = program.main_model
    lines.append("  out_arg [shape=plaintext, label=\"out_arg\"];")
    for final in main.finals():
        lines.append(f"  {_node(main, final)} -> out_arg [style=bold, penwidth=2];")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _cluster(program: Program, model: DialogueModel, index: int) -> list[str]:
    lines = [f"  subgraph cluster_{index} {{", "    style=dotted;",
             f"    label={_quote(format_term(model.head))};"]
    for situation in model.situations:
        shape = "doublecircle" if situation.type == FINAL else "circle"
        style = ", style=bold, penwidth=2" if situation.type == RECURSIVE else ""
        label = f"{format_term(situation.id)}\\n{situation.type}"
        lines.append(f"    {_node(model, situation)} [shape={shape}{style}, "
                     f"label={_quote(label)}];")
    lines.append("  }")
    for situation in model.situations:
        lines.extend(_arcs(program, model, situation))
    return lines


def _arcs(program: Program, model: DialogueModel, situation: Situation) -> list[str]:
    lines = []
    source = _node(model, situation)
    if situation.type == RECURSIVE and situation.embedded_dm is not None:
        key = functor_of(situation.embedded_dm)
        embedded = program.models.get(key) if key else None
        if embedded is not None:
            lines.append(f"  {source} -> {_node(embedded, embedded.initial)} "
                         "[style=bold, penwidth=2, arrowhead=vee, label=\"pipe\"];")
    for number, arc in enumerate(situation.arcs):
        label = _quote(f"{_short(arc.expectation)}:{_short(arc.action)}")
        target = deref(arc.next)
        if isinstance(target, Struct) and target.functor == "apply":
            dot = _node(model, situation, f"/f{number}")
            function = deref(target.args[0])
            name = functor_of(function)
            lines.append(f"  {dot} [shape=point, width=0.18, xlabel="
                         f"{_quote(name[0] if name else '?')}];")
            lines.append(f"  {source} -> {dot} [label={label}];")
            for value in _values(program, model, name[0] if name else ""):
                lines.append(f"  {dot} -> {_node(model, value)} [style=dashed];")
            continue
        for candidate in model.situations:
            if functor_of(candidate.id) == functor_of(target):
                lines.append(f"  {source} -> {_node(model, candidate)} [label={label}];")
                break
    return lines


def _values(program: Program, model: DialogueModel, function: str) -> list[Situation]:
    declared = getattr(program.functions.get(function), "values", None)
    if declared is None:
        return list(model.situations)
    return [s for s in model.situations if functor_of(s.id)[0] in declared]  # type: ignore[index]


def _short(term: Term) -> str:
    """An arc label part: functions shown by name (``f``), the rest as written."""
    term = deref(term)
    if isinstance(term, Struct) and term.functor == "apply":
        name = functor_of(deref(term.args[0]))
        return name[0] if name else "apply"
    if isinstance(term, tuple):
        return "[" + ",".join(_short(item) for item in term) + "]"
    if isinstance(term, Struct) and term.functor == "get" and term.arity >= 1:
        return format_term(term.args[0])
    return format_term(term)


def _node(model: DialogueModel, situation: Situation, suffix: str = "") -> str:
    name = functor_of(situation.id)
    assert name is not None
    index = model.situations.index(situation)
    return f"\"{model.name}/{name[0]}/{index}{suffix}\""


def _quote(text: str) -> str:
    return "\"" + text.replace("\\", "\\\\").replace("\"", "\\\"").replace("\\\\n", "\\n") + "\""
