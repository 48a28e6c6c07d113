"""Reading the files people give homebot, bounded: every format has a size limit.

A world, a dialogue model, a knowledge base, a JSHOP2 domain, a map, an event log or a
recording is read through ``read_text_file`` or ``read_bytes_file``, which read at most
the format's limit and one byte more: a file over the limit (or a device that never
ends, such as ``/dev/zero``) is refused with an error naming the file, the limit and the
format, and never read whole. Pipes and devices are read like files, within the same
bound, so ``homebot world check <(generate-world)`` still works. This module imports
nothing of homebot but its errors, so every layer may use it.
"""

from __future__ import annotations

import sys
from pathlib import Path
from types import MappingProxyType

from homebot.errors import HomebotError

__all__ = ["SIZE_LIMITS", "read_bytes_file", "read_text_file", "read_typed_line", "size_text"]

_MIB = 1 << 20

#: The largest file of each format, in bytes; the shipped files are far smaller (the
#: largest, a test corpus, is 40 KB), so a file past these is a mistake or an attack.
#: A 2 MiB world of 34,000 objects is read and checked in about 4 s of CPU (with libyaml;
#: PyYAML's own parser alone took over 30 s).
SIZE_LIMITS = MappingProxyType({
    "yaml": 2 * _MIB,  # worlds, task files, dialogue models, maps, robot profiles, KB YAML
    "text": 4 * _MIB,  # KB text, JSHOP2 domains and problems, Golog, SitLog .dm, input lines
    "events": 64 * _MIB,  # an event log (JSON lines) to draw a run from
    "image": 64 * _MIB,  # a map's PGM or PNG
    "audio": 64 * _MIB,  # a WAV recording (a command is at most a minute: 2 MB at 16 kHz)
})


def size_text(size: int) -> str:
    """A byte count as people read it: ``8 MiB``, ``512 KiB``, ``900 bytes``."""
    for unit, scale in (("GiB", 1 << 30), ("MiB", _MIB), ("KiB", 1 << 10)):
        if size >= scale:
            return f"{size / scale:g} {unit}"
    return f"{size} bytes"


def read_bytes_file(path: Path | str, error_type: type[HomebotError], kind: str,
                    what: str = "file") -> bytes:
    """The bytes of ``path``, a file of format ``kind`` (a key of ``SIZE_LIMITS``).

    A missing, unreadable or oversized file raises ``error_type`` naming the file; at most
    the limit and one byte are read, whatever the file is.
    """
    path = Path(path)
    limit = SIZE_LIMITS[kind]
    try:
        with path.open("rb") as handle:
            data = handle.read(limit + 1)
    except FileNotFoundError:
        raise error_type(f"{path}: cannot read it (no such file); check the path") from None
    except IsADirectoryError:
        raise error_type(f"{path}: cannot read it (it is a folder); give a {what}") from None
    except OSError as error:
        raise error_type(f"{path}: cannot read it ({error.strerror or error}); check the "
                         "path and its permissions") from None
    if len(data) > limit:
        raise error_type(f"{path}: larger than {size_text(limit)}, the limit for a {what}; "
                         "give a smaller file (is it the right one?)")
    return data


def read_text_file(path: Path | str, error_type: type[HomebotError], kind: str,
                   what: str = "file") -> str:
    """The UTF-8 text of ``path``, bounded as ``read_bytes_file``; other encodings are
    refused with the byte where decoding failed."""
    data = read_bytes_file(path, error_type, kind, what)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise error_type(f"{path}: not UTF-8 text (byte {error.start + 1}: {error.reason}); "
                         "give a UTF-8 text file") from None


def read_typed_line(prompt: str, error_type: type[HomebotError]) -> str:
    """A line typed at ``prompt``, like ``input``, read within ``SIZE_LIMITS["text"]``.

    A terminal is read by ``input`` (a person's line, with line editing); piped input is
    read at most the limit at a time, so ``homebot chat < /dev/zero`` is refused with
    ``error_type`` instead of growing without end. The end of input raises ``EOFError``.
    """
    if sys.stdin.isatty():
        return input(prompt)
    sys.stdout.write(prompt)
    sys.stdout.flush()
    limit = SIZE_LIMITS["text"]
    line = sys.stdin.readline(limit + 1)
    if not line:
        raise EOFError
    line = line.removesuffix("\n")
    if len(line) > limit:
        raise error_type(f"<stdin>: a line longer than {size_text(limit)}, the limit for "
                         "one typed line; give one command or answer a line")
    return line
