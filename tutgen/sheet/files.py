"""Writing a sheet's files into its staging directory: by the command (tutgen/sheet/run.py) and, for a
local executor, by the workers that build the sheets (tutgen/sheet/build.py)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from tutgen.errors import UsageError


def write_files(root: Path, files: Sequence[tuple[str, str | bytes | None]], shown: Path) -> None:
    """Write ``files`` (paths relative to ``root``) into ``root``, a staging directory; a None content is
    a file already written there. An OSError is a UsageError that names the file as it will be, under
    ``shown`` (-o)."""
    for name, content in files:
        if content is None:
            continue
        path = root / name
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            if isinstance(content, bytes):
                path.write_bytes(content)
            else:
                with open(path, "w", encoding="utf-8", newline="\n") as fh:
                    fh.write(content)
        except OSError as err:
            raise UsageError(f"cannot write {shown / name}: {err.strerror or err}; nothing was written") from None
