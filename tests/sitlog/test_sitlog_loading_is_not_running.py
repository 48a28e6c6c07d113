"""Opening a dialogue model runs none of its code; running it loads code only from trusted places.

``show`` and ``check`` read a model as data. ``run`` imports user functions from ``.py``
files in the model's own folder, homebot's own modules and installed entry points, and
says which; ``include`` stays in the model's folder. Each function file here leaves a
mark when it is imported, so a test sees whether it ran.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from homebot.cli import main
from homebot.errors import DialogueError
from homebot.sitlog import load_program

# A function file that leaves a mark beside itself when imported, and greets by name.
FUNCTIONS = """
from pathlib import Path

Path(__file__).with_name("imported.mark").write_text("ran", encoding="utf-8")


def greeting(env, name):
    return "hello"


def user_functions():
    return {"greeting": greeting}
"""

MODEL = """
functions: [{functions}]
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        arcs:
          - "name(X) : say(apply(greeting(N), [X])) => fs"
      - {{id: fs, type: final}}
"""


def _model(folder: Path, functions: str, functions_folder: Path | None = None) -> Path:
    (functions_folder or folder).mkdir(parents=True, exist_ok=True)
    folder.mkdir(parents=True, exist_ok=True)
    (functions_folder or folder).joinpath("greetings.py").write_text(FUNCTIONS, encoding="utf-8")
    model = folder / "model.yaml"
    model.write_text(MODEL.format(functions=functions), encoding="utf-8")
    return model


def _imported(folder: Path) -> bool:
    return (folder / "imported.mark").exists()


@pytest.mark.parametrize("command", ["show", "check"])
def test_show_and_check_import_nothing_the_model_names(
        tmp_path: Path, command: str, capsys: pytest.CaptureFixture[str]) -> None:
    model = _model(tmp_path, "greetings.py")
    assert main(["sitlog", command, str(model)]) == 0
    assert not _imported(tmp_path)
    if command == "check":
        out = capsys.readouterr().out
        assert "ok: 1 dialogue model, 2 situations" in out
        assert f"functions from {tmp_path / 'greetings.py'}: not imported" in out


def test_show_and_check_still_find_a_misnamed_situation_without_running_code(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    model = _model(tmp_path, "greetings.py")
    model.write_text(model.read_text(encoding="utf-8").replace("=> fs", "=> fz"),
                     encoding="utf-8")
    assert main(["sitlog", "check", str(model)]) == 2
    assert "unknown next situation 'fz'" in capsys.readouterr().err
    assert not _imported(tmp_path)


def test_run_loads_a_function_file_in_the_models_folder_and_says_so(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    model = _model(tmp_path, "greetings.py")
    assert main(["sitlog", "run", str(model), "--input", "name(ana)"]) == 0
    captured = capsys.readouterr()
    assert _imported(tmp_path)
    assert f"note: user functions from {tmp_path / 'greetings.py'}" in captured.err
    assert "robot: hello" in captured.out


@pytest.mark.parametrize("command", ["run", "show", "check"])
@pytest.mark.parametrize("written", ["../elsewhere/greetings.py", "{elsewhere}/greetings.py"])
def test_a_function_file_outside_the_models_folder_is_refused_unrun(
        tmp_path: Path, command: str, written: str,
        capsys: pytest.CaptureFixture[str]) -> None:
    elsewhere = tmp_path / "elsewhere"
    model = _model(tmp_path / "model", written.format(elsewhere=elsewhere), elsewhere)
    assert main(["sitlog", command, str(model)]) == 2
    err = capsys.readouterr().err
    assert f"{model}, line 2, column" in err
    assert "is outside the model's folder" in err and "Traceback" not in err
    assert not _imported(elsewhere)


def test_a_module_name_that_is_not_trusted_is_refused_before_import(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # greetings is importable (its folder is on sys.path), but a model may not name it
    monkeypatch.syspath_prepend(str(tmp_path / "site"))
    model = _model(tmp_path / "model", "greetings", tmp_path / "site")
    with pytest.raises(DialogueError, match=r"line 2.*'greetings' is neither a \.py file "
                                            r"in the model's folder"):
        load_program(model)
    assert not _imported(tmp_path / "site")


def test_an_installed_entry_point_is_trusted(tmp_path: Path,
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    site = tmp_path / "site"
    site.mkdir()
    (site / "shouting_functions.py").write_text(FUNCTIONS, encoding="utf-8")
    info = site / "shouting-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: shouting\nVersion: 1.0\n",
                                   encoding="utf-8")
    (info / "entry_points.txt").write_text(
        "[homebot.sitlog_functions]\nshouting = shouting_functions\n", encoding="utf-8")
    monkeypatch.syspath_prepend(str(site))
    model = _model(tmp_path / "model", "shouting")
    assert load_program(model, run_code=False).unloaded_functions == (
        "shouting_functions (entry point shouting)",)
    assert not _imported(site)
    program = load_program(model)
    assert _imported(site)
    assert program.function_sources == ("shouting_functions (entry point shouting)",)
    assert "greeting" in program.functions


@pytest.mark.parametrize("include", ["/etc/passwd", "../secret.yaml"])
@pytest.mark.parametrize("command", ["show", "check", "run"])
def test_an_include_outside_the_models_folder_is_refused(
        tmp_path: Path, include: str, command: str,
        capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "secret.yaml").write_text("dialogue_models: []\n", encoding="utf-8")
    folder = tmp_path / "model"
    folder.mkdir()
    model = folder / "model.yaml"
    model.write_text(textwrap.dedent(f"""\
        # a model that tries to read beyond its folder
        include: [{include}]
        dialogue_models: []
        """), encoding="utf-8")
    assert main(["sitlog", command, str(model)]) == 2
    err = capsys.readouterr().err
    assert f"{model}, line 2, column 11: include '{include}' is outside the model's folder" in err
    assert "root:" not in err  # nothing of /etc/passwd is quoted


def test_an_include_in_the_models_folder_is_read(tmp_path: Path) -> None:
    (tmp_path / "part").mkdir()
    (tmp_path / "part" / "common.yaml").write_text(textwrap.dedent("""\
        dialogue_models:
          - id: common
            situations:
              - {id: is, type: speech, arcs: ["bye : empty => fs"]}
              - {id: fs, type: final}
        """), encoding="utf-8")
    (tmp_path / "model.yaml").write_text("include: [part/common.yaml]\nmain: common\n",
                                         encoding="utf-8")
    assert ("common", 0) in load_program(tmp_path / "model.yaml").models


@pytest.mark.parametrize("name", ["appendix_a", "appendix_a.dm", "behaviours", "butler"])
def test_the_shipped_models_check_with_homebots_own_functions(
        name: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog", "check", name]) == 0
    out = capsys.readouterr().out
    assert "ok:" in out and "(homebot's own)" in out and "not imported" not in out
