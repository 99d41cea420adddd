"""The external formatters generated code goes through — one registry (clang-format for C, ruff
for Python, rustfmt for Rust), each run on text in memory (stdin → stdout; clang-format on
private copies in a temporary folder) so output is deterministic, each with a timeout. A
missing, failing or hanging formatter is a generation error naming the tool and how to install
it: generated code is never written unformatted."""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import subprocess
import tempfile
import zlib
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from canspec import resources
from canspec.render import format_cache

TIMEOUT_S = 300
# The formatters' versions are part of the output: CI installs exactly these (.ci/setup.d/).
RUFF_VERSION = "0.17.6"
CLANG_FORMAT_VERSION = "14.0.6"


class FormatterError(RuntimeError):
    """A formatter is missing, failed or timed out (generate.py reports it as one line, no traceback)."""


def _ruff_binary() -> str | None:
    try:
        from ruff.__main__ import find_ruff_bin  # type: ignore[import-not-found,import-untyped,unused-ignore]
    except ImportError:
        return None
    return str(find_ruff_bin())


def _clang_format_wheel() -> str | None:
    """The binary of the `clang-format` wheel (canspec depends on the pinned one), if installed."""
    spec = importlib.util.find_spec("clang_format")
    if spec is None or spec.origin is None:
        return None
    exe = Path(spec.origin).parent / "data" / "bin" / ("clang-format.exe" if os.name == "nt" else "clang-format")
    return str(exe) if exe.is_file() else None


def _clang_format_binary() -> str | None:
    """The wheel's clang-format before any other on PATH: another version lays the C out
    differently, and a PATH entry may be a shim that costs more than the formatting."""
    return _clang_format_wheel() or shutil.which("clang-format")


@lru_cache(maxsize=None)
def _version(exe: str) -> str | None:
    """The x.y.z an executable's `--version` prints (None when it prints none or fails)."""
    try:
        proc = subprocess.run([exe, "--version"], capture_output=True, check=False, timeout=TIMEOUT_S)
    except (OSError, subprocess.TimeoutExpired):
        return None
    found = re.search(r"\b(\d+\.\d+\.\d+)\b", proc.stdout.decode("utf-8", "replace"))
    return found.group(1) if found else None


@dataclass(frozen=True)
class Formatter:
    name: str
    install: str  # how to install it: the hint of the error when it is missing
    locate: Callable[[], str | None]  # the executable, or None when it is not installed
    pinned: str | None = None  # the version whose layout the committed output has (None: stable layout)

    def version_note(self) -> str | None:
        """A warning when the installed version is not the pinned one: the code is the same, but
        its layout may differ from what other machines write, so `gen --check` may see changes."""
        exe = self.locate()
        found = _version(exe) if exe is not None and self.pinned is not None else None
        if found is None or found == self.pinned:
            return None
        return (f"{self.name} {found} is installed, but generated code is laid out by {self.name} {self.pinned}: files may differ "
                f"in layout from other machines' output (pip install {self.name}=={self.pinned})")

    def executable(self) -> str:
        exe = self.locate()
        if exe is None:
            raise FormatterError(f"{self.name} not found; generated code is formatted with it (install: {self.install})")
        return exe

    def run(self, args: list[str], text: str, what: str, cached: bool = True) -> str:
        """`text` as the tool writes it to stdout, given `args`; `what` names the file in errors.
        `cached`: from format_cache when this tool formatted the same text with the same arguments
        before (False: the tool's effect is elsewhere, `clang-format -i`)."""
        exe = self.executable()
        entry = format_cache.key(exe, args, text) if cached else None
        if (formatted := format_cache.lookup(entry)) is not None:
            return formatted
        try:
            proc = subprocess.run([exe, *args], input=text.encode("utf-8"), capture_output=True, check=False, timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            raise FormatterError(f"{self.name} took more than {TIMEOUT_S} s on {what}") from None
        if proc.returncode != 0:
            raise FormatterError(f"{self.name} failed on {what}: {proc.stderr.decode('utf-8', 'replace').strip()[:2000]}")
        formatted = proc.stdout.decode("utf-8")
        format_cache.keep(entry, formatted)
        return formatted


# rustfmt is not pinned: its default style is stable across versions (Rust's style guarantee).
FORMATTERS = {
    "clang-format": Formatter(
        "clang-format", f"pip install clang-format=={CLANG_FORMAT_VERSION}, or apt-get install clang-format", _clang_format_binary, CLANG_FORMAT_VERSION
    ),
    "ruff": Formatter("ruff", f"pip install ruff=={RUFF_VERSION}", _ruff_binary, RUFF_VERSION),
    "rustfmt": Formatter("rustfmt", "rustup component add rustfmt", lambda: shutil.which("rustfmt")),
}


def version_notes(names: Iterable[str]) -> list[str]:
    """The version warnings of the named formatters, in registry order."""
    wanted = set(names)
    return [note for name, formatter in FORMATTERS.items() if name in wanted and (note := formatter.version_note()) is not None]


def _clang_format_args(name: str, style: Path) -> list[str]:
    return [f"--style=file:{style}", f"--assume-filename={name}"]


def clang_format(text: str, name: str, style: Path) -> str:
    """C in the style of the given .clang-format file."""
    return FORMATTERS["clang-format"].run(_clang_format_args(name, style), text, name)


def ruff_format(source: str, filename: str, package: str, line_length: int) -> str:
    """Python as ruff writes it, with the Python target's settings and no config files: imports
    sorted (isort's order of names, which the templates do not reproduce), then formatted."""
    ruff = FORMATTERS["ruff"]
    common = ["--isolated", f"--line-length={line_length}", "--target-version=py310", f"--stdin-filename={filename}", "-"]
    isort = ["check", "--select=I", "--fix", "--exit-zero", "--quiet", "--config", f"lint.isort.known-first-party = [{package!r}]"]
    return ruff.run(["format", *common], ruff.run([*isort, *common], source, filename), filename)


def rustfmt(text: str, what: str) -> str:
    """Rust in rustfmt's default style. Its settings come from the committed templates/rust/rustfmt.toml:
    without --config-path, rustfmt reads a rustfmt.toml in the working directory or above it (the
    user's project) and lays the generated crate out as that file says."""
    config = resources.templates_dir() / "rust" / "rustfmt.toml"
    return FORMATTERS["rustfmt"].run(["--edition", "2021", "--emit", "stdout", "--config-path", str(config)], text, what)


# clang-format's and rustfmt's time and memory grow faster than the text (a 22 MB C header took 30 s
# and 2 GB; a 25 MB Rust module 640 MB), so a large file is formatted in chunks cut after a
# top-level item: a closing brace in column 0 and one blank line before the next item. Both tools
# format such items independently (the C style aligns only consecutive lines; rustfmt reorders only
# contiguous `use` lines), so the chunks give the bytes of the whole; smaller files go whole.
# clang-format: 64 KiB on average (the Ford DBC's messages header: 2.6 CPU s, 2.9 in 256 KiB pieces
# cut at offsets; the 1,000-message one 9.4 s, 9.7).
CHUNK_CHARS = 64 * 1024
# rustfmt's chunks are larger: its cost per chunk outweighs the growth (the Ford DBC's crate: 42 chunks
# of 256 KiB on average 1.8 CPU s, 17 of 1 MiB 1.5 s, each rustfmt then under 60 MB).
RUSTFMT_CHUNK_CHARS = 1024 * 1024
PROCESS_CHARS = 256 * 1024  # the text worth another clang-format process beside the first
_CUT = re.compile(r"\n}\n\n(?=\S)")


def chunks(text: str, size: int = CHUNK_CHARS) -> list[str]:
    """The text cut into pieces of about `size` characters on average, each ending in an item's '}\\n'
    (the blank line after it is dropped and restored by the join). Where to cut is decided by each
    item's own text (a hash below its share of `size`), not by offsets: an edit changes only the
    pieces that hold the edited items, and format_cache has the others. A piece reaching 4 × `size`
    is cut anyway, at its next item."""
    pieces, start, item = [], 0, 0
    for cut in _CUT.finditer(text):
        end = cut.start() + 3
        if zlib.crc32(text[item:end].encode("utf-8")) * size < (end - item) << 32 or end - start >= 4 * size:
            pieces.append(text[start:end])
            start = cut.end()
        item = cut.end()
    return [*pieces, text[start:]]


def in_chunks(text: str, fmt: Callable[[str], str], size: int = CHUNK_CHARS) -> str:
    """`fmt(text)`, run on the chunks of a large text in parallel processes (one per core)."""
    pieces = chunks(text, size) if len(text) > size else [text]
    if len(pieces) == 1:
        return fmt(text)
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        return "\n".join(pool.map(fmt, pieces))


def clang_format_files(texts: dict[str, str], style: Path, size: int = CHUNK_CHARS) -> dict[str, str]:
    """Every text of {file name: text} in the style of the .clang-format file, large ones cut in
    chunks. A clang-format process costs 75 ms before it reads a byte, so the pieces are written
    to a private folder and formatted in place by one process per core (`clang-format -i`, many
    files each): 1,000 messages format in 9.4 CPU s instead of 12 with a process per piece. Where
    that folder cannot be written (a full or read-only TMPDIR, a file size limit), each piece
    goes through stdin instead: the same bytes, only slower."""
    try:
        return _clang_format_copies(texts, style, size)
    except OSError:
        return {name: in_chunks(text, lambda piece, name=name: clang_format(piece, name, style), size) for name, text in texts.items()}


def _clang_format_copies(texts: dict[str, str], style: Path, size: int) -> dict[str, str]:
    pieces = [(name, piece) for name, text in texts.items() for piece in (chunks(text, size) if len(text) > size else [text])]
    exe = FORMATTERS["clang-format"].executable()
    keys = [format_cache.key(exe, _clang_format_args(name, style), piece) for name, piece in pieces]
    formatted = [format_cache.lookup(key) for key in keys]
    missing = [i for i, text in enumerate(formatted) if text is None]
    if missing:
        with tempfile.TemporaryDirectory(prefix="canspec-c-") as folder:
            paths = {i: Path(folder) / f"{i:05d}-{pieces[i][0]}" for i in missing}
            for i, path in paths.items():
                path.write_bytes(pieces[i][1].encode("utf-8"))
            groups = _balanced(list(paths.values()), [len(pieces[i][1]) for i in missing], os.cpu_count() or 2)
            with ThreadPoolExecutor(max_workers=len(groups)) as pool:
                list(pool.map(lambda group: _clang_format_in_place(group, style, folder), groups))
            for i, path in paths.items():
                formatted[i] = path.read_bytes().decode("utf-8")
                format_cache.keep(keys[i], formatted[i])
    out: dict[str, list[str]] = {name: [] for name in texts}
    for (name, _), text in zip(pieces, formatted):
        out[name].append(text or "")
    return {name: "\n".join(parts) for name, parts in out.items()}


def _balanced(items: list[Path], sizes: list[int], bins: int) -> list[list[Path]]:
    """The items in at most `bins` groups of about equal total size (largest first, each to the
    lightest group); one group for each PROCESS_CHARS of text (a process costs 75 ms to start)."""
    bins = max(1, min(bins, sum(sizes) // PROCESS_CHARS))
    groups: list[list[Path]] = [[] for _ in range(bins)]
    loads = [0] * bins
    for size, item in sorted(zip(sizes, items), key=lambda pair: -pair[0]):
        lightest = loads.index(min(loads))
        groups[lightest].append(item)
        loads[lightest] += size
    return [sorted(group) for group in groups if group]


def _clang_format_in_place(paths: list[Path], style: Path, folder: str) -> None:
    headers = list(dict.fromkeys(path.name.split("-", 1)[1] for path in paths))  # the chunks of one header name it once
    what = ", ".join(headers[:3]) + (" …" if len(headers) > 3 else "")
    try:
        FORMATTERS["clang-format"].run([f"--style=file:{style}", "-i", *map(str, paths)], "", what, cached=False)
    except FormatterError as exc:  # its message names the private folder's files: name the headers
        raise FormatterError(str(exc).replace(folder + os.sep, "")) from None

