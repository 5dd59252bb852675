"""Every file the package writes goes through here: checked before the work, written atomically.

The policy (docs/errors.md#output-files):

- **checked first**: :func:`check_outputs` runs before any work starts. A path that is one of the
  inputs (same file, however it is spelled), two outputs that are the same file, a path that is
  a folder, a folder that cannot be made (a file stands where a folder should be, or no write
  permission), or a figure whose extension is not a format matplotlib saves are refused with
  :class:`OutputError`; so is an existing file, unless ``force`` is given;
- **written atomically**: :func:`write_files` writes each file to a temporary file in its own
  folder and renames it over the target with :func:`os.replace` only once every file of the call
  is complete, so an error leaves no partial file, and no half of a pair.

The library functions (:meth:`Params.save`, the figure helpers) write atomically and overwrite
as asked; refusing existing files is the command line's policy (``--force``).
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Callable, Iterable, Sequence
from contextlib import suppress
from functools import cache
from os import PathLike
from pathlib import Path

from .errors import OutputError

#: Writes a whole file at the path it is given.
Writer = Callable[[Path], None]


@cache
def image_formats() -> tuple[str, ...]:
    """The extensions (without the dot) that matplotlib's ``savefig`` writes, e.g. png, pdf, svg."""
    from matplotlib.figure import Figure

    return tuple(sorted(Figure().canvas.get_supported_filetypes()))


def image_format(path: str | PathLike[str], label: str = "figure") -> str:
    """The format of a figure path (its extension, lower case), refused with :class:`OutputError`
    when matplotlib cannot write it."""
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in image_formats():
        got = f"extension .{suffix}" if suffix else "no extension"
        raise OutputError(
            f"{label} {os.fspath(path)!s} has {got}: expected an image format that matplotlib "
            f"writes, one of {', '.join('.' + name for name in image_formats())}",
            kind="invalid_choice",
            field=label,
            value=os.fspath(path),
            expected=sorted(image_formats()),
            got=suffix,
        )
    return suffix


def _same_file(a: Path, b: Path) -> bool:
    with suppress(OSError, ValueError):
        if os.path.samefile(a, b):
            return True
    return a.resolve() == b.resolve()


def check_folder(
    folder: str | PathLike[str], label: str = "output folder", *, field: str | None = None
) -> Path:
    """``folder`` as a path, refused with :class:`OutputError` unless it is a folder or can be
    made (its nearest existing ancestor is a writable folder). Nothing is created. ``label``
    starts the message; ``field`` is the option the error names (``label`` when not given)."""
    field = label if field is None else field
    folder = Path(folder)
    existing = folder.absolute()
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        raise OutputError(
            f"{label}: the folder {folder} cannot be made, {existing} is a file"
            if existing != folder.absolute()
            else f"{label}: {folder} is a file, not a folder",
            kind="no_folder",
            field=field,
            value=os.fspath(folder),
        )
    if not os.access(existing, os.W_OK | os.X_OK):
        raise OutputError(
            f"{label}: no permission to write in the folder {existing}",
            kind="no_permission",
            field=field,
            value=os.fspath(folder),
        )
    return folder


def check_output(
    path: str | PathLike[str],
    *,
    label: str = "output",
    inputs: Iterable[str | PathLike[str]] = (),
    force: bool = False,
    image: bool = False,
) -> Path:
    """One output path, checked as the module docstring says; returns it as a :class:`Path`."""
    if not os.fspath(path):
        raise OutputError(
            f"{label} must be a file name, got an empty path", kind="empty_path", field=label, value=""
        )
    target = Path(path)
    if image:
        image_format(target, label)
    for source in inputs:
        if _same_file(target, Path(source)):
            raise OutputError(
                f"{label} {target} is the input file {source}: refusing to overwrite the input "
                "(give another file name)",
                kind="is_input",
                field=label,
                value=os.fspath(target),
            )
    if target.is_dir():
        raise OutputError(
            f"{label} {target} is a folder: expected a file name",
            kind="is_folder",
            field=label,
            value=os.fspath(target),
        )
    if (target.exists() or target.is_symlink()) and not force:
        raise OutputError(
            f"{label} {target} exists: refusing to overwrite it (pass --force to replace it)",
            kind="exists",
            field=label,
            value=os.fspath(target),
        )
    check_folder(target.parent, f"{label} {target}", field=label)
    return target


def check_outputs(
    outputs: Sequence[tuple[str, str | PathLike[str], bool]],
    *,
    inputs: Iterable[str | PathLike[str]] = (),
    force: bool = False,
) -> list[Path]:
    """Every output of one command, each ``(label, path, is_image)``: :func:`check_output` on
    each, and no two the same file."""
    sources = list(inputs)
    checked: list[tuple[str, Path]] = []
    for label, path, image in outputs:
        target = check_output(path, label=label, inputs=sources, force=force, image=image)
        for other_label, other in checked:
            if _same_file(target, other):
                raise OutputError(
                    f"{label} and {other_label} are the same file {target}: give two names",
                    kind="same_file",
                    field=label,
                    value=os.fspath(target),
                )
        checked.append((label, target))
    return [target for _, target in checked]


def _temporary(path: Path) -> Path:
    """A new empty file beside ``path`` (same folder, so that the rename is atomic), made with
    the permissions a plain ``open`` would give it."""
    while True:
        temporary = path.with_name(f".{path.name}.{secrets.token_hex(4)}.part")
        try:
            os.close(os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
        except FileExistsError:  # pragma: no cover - 32 random bits taken
            continue
        return temporary


def write_files(files: Sequence[tuple[str | PathLike[str], Writer]]) -> list[Path]:
    """Writes every ``(path, writer)`` atomically: each writer fills a temporary file in the
    target's folder (made if needed), and only when all have succeeded are they renamed onto the
    targets, so a failing writer leaves no target touched. Each rename is atomic; the renames
    together are not: should one fail after another succeeded (a permission changed in between),
    the earlier target is already replaced. A failure removes the temporary files and raises
    :class:`OutputError` naming the path (or re-raises the writer's own error)."""
    done: list[tuple[Path, Path]] = []
    try:
        for path, write in files:
            target = Path(path)
            try:
                target.parent.mkdir(parents=True, exist_ok=True)
                temporary = _temporary(target)
            except OSError as error:
                raise OutputError(
                    f"cannot write {target}: {error.strerror or error}",
                    kind="write_failed",
                    value=os.fspath(target),
                ) from None
            done.append((temporary, target))
            try:
                write(temporary)
            except OSError as error:
                raise OutputError(
                    f"cannot write {target}: {error.strerror or error}",
                    kind="write_failed",
                    value=os.fspath(target),
                ) from None
        for temporary, target in done:
            try:
                os.replace(temporary, target)
            except OSError as error:
                raise OutputError(
                    f"cannot write {target}: {error.strerror or error}",
                    kind="write_failed",
                    value=os.fspath(target),
                ) from None
    except BaseException:
        for temporary, _ in done:
            with suppress(OSError):
                os.unlink(temporary)
        raise
    return [target for _, target in done]


def text_writer(text: str) -> Writer:
    """A writer of ``text`` as UTF-8."""

    def write(path: Path) -> None:
        path.write_text(text, encoding="utf-8")

    return write


def write_text(path: str | PathLike[str], text: str) -> Path:
    """Writes ``text`` (UTF-8) to ``path`` atomically."""
    return write_files([(path, text_writer(text))])[0]
