"""Files people give are read within a size limit per format, never whole past it."""

from __future__ import annotations

import os
import tracemalloc
from pathlib import Path

import pytest

from homebot.errors import HomebotError, WorldError
from homebot.files import SIZE_LIMITS, read_bytes_file, read_text_file, size_text


def test_a_file_within_its_limit_is_read_whole(tmp_path: Path) -> None:
    path = tmp_path / "world.yaml"
    path.write_text("name: café\n", encoding="utf-8")
    assert read_text_file(path, WorldError, "yaml") == "name: café\n"
    assert read_bytes_file(path, WorldError, "yaml") == "name: café\n".encode()


def test_a_file_one_byte_past_its_limit_is_refused_naming_file_limit_and_format(
        tmp_path: Path) -> None:
    path = tmp_path / "huge.yaml"
    with path.open("wb") as handle:  # sparse: no disk or time spent on it
        handle.truncate(SIZE_LIMITS["yaml"] + 1)
    with pytest.raises(WorldError, match=f"{path}: larger than 2 MiB, the limit for a world "
                                         "file; give a smaller file"):
        read_text_file(path, WorldError, "yaml", "world file")
    with path.open("r+b") as handle:
        handle.truncate(SIZE_LIMITS["yaml"])
    assert len(read_bytes_file(path, WorldError, "yaml")) == SIZE_LIMITS["yaml"]


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero here")
def test_an_endless_device_is_read_only_to_the_limit() -> None:
    # `world check /dev/zero` once grew to 9.4 GB in 60 s
    tracemalloc.start()
    try:
        with pytest.raises(WorldError, match="/dev/zero: larger than 2 MiB"):
            read_text_file("/dev/zero", WorldError, "yaml", "world file")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 2 * SIZE_LIMITS["yaml"]


def test_missing_folders_and_other_encodings_are_named(tmp_path: Path) -> None:
    with pytest.raises(HomebotError, match=r"nothing\.kb: cannot read it \(no such file\)"):
        read_text_file(tmp_path / "nothing.kb", HomebotError, "text")
    with pytest.raises(HomebotError, match="cannot read it \\(it is a folder\\); give a map"):
        read_bytes_file(tmp_path, HomebotError, "image", "map")
    latin = tmp_path / "latin.kb"
    latin.write_bytes("id=>josé, ok".encode("latin-1"))
    with pytest.raises(HomebotError, match=r"latin\.kb: not UTF-8 text \(byte 8: invalid "
                                           r"continuation byte\); give a UTF-8 text file"):
        read_text_file(latin, HomebotError, "text")


def test_sizes_are_written_as_people_read_them() -> None:
    assert [size_text(n) for n in (900, 512 << 10, 8 << 20, 3 << 29)] == [
        "900 bytes", "512 KiB", "8 MiB", "1.5 GiB"]
