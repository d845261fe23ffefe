"""Refit garments onto avatars and certify the results, from Python.

Each function runs the command of the same name of ``garment-retarget`` in this process
on typed options (``batch`` starts one process per job, as the command does) and returns what it wrote as
dicts and NumPy arrays. Meshes are file paths or ``(V, F)`` pairs of arrays (#V×3 floats,
#F×3 0-based ints). Errors raise ``UsageError`` (a bad option), ``InputError`` (a bad
input file; both are ``ValueError``) or ``OutputError`` (an ``OSError``) with the command
line's messages.
"""

from __future__ import annotations

import csv
import json
import os
import tempfile
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from ._core import (InputError, Outcome, OutputError, RetargetOptions, RetargetResult, ShrinkOptions, ShrinkResult,
                    UsageError, ValidateOptions, ValidateResult, formats, outcome_names, parameters, read_mesh,
                    run_command, run_retarget, run_shrink, run_validate, version)

__all__ = [
    "InputError",
    "Outcome",
    "OutputError",
    "RetargetOptions",
    "RetargetResult",
    "ShrinkOptions",
    "ShrinkResult",
    "UsageError",
    "ValidateOptions",
    "ValidateResult",
    "batch",
    "formats",
    "parameters",
    "program_path",
    "read_mesh",
    "retarget",
    "retarget_options",
    "run_retarget",
    "run_shrink",
    "run_validate",
    "shrink",
    "shrink_options",
    "validate",
    "validate_options",
    "version",
    "write_mesh",
]
__version__ = version

#: Exit codes of the command line by name (docs/exit-codes.md), from its outcome table.
STATUS_BY_EXIT_CODE = dict(outcome_names)


def program_path() -> str:
    """The ``garment-retarget`` program installed with this package, which batch jobs run."""
    path = Path(__file__).with_name("garment-retarget")
    if not path.exists():
        raise OutputError(f"{path}: the garment-retarget program is missing from the package")
    return str(path)


def write_mesh(path: str | os.PathLike, vertices: Any, faces: Any) -> None:
    """Writes V (#V×3) and F (#F×3, 0-based) as an OBJ at full precision."""
    from ._core import write_mesh as _write

    _write(path, np.asarray(vertices, dtype=np.float64), np.asarray(faces, dtype=np.int32))


def _mesh_file(mesh: Any, folder: str, name: str) -> str:
    """A path for `mesh`: itself when it is a path, else the (V, F) pair written into `folder`."""
    if isinstance(mesh, (str, os.PathLike)):
        return os.fspath(mesh)
    if isinstance(mesh, (tuple, list)) and len(mesh) == 2:
        path = os.path.join(folder, name + ".obj")
        write_mesh(path, mesh[0], mesh[1])
        return path
    raise TypeError(f"{name}: expected a file path or a (V, F) pair of arrays, got {type(mesh).__name__}")


def _option_arguments(options: dict[str, Any]) -> list[str]:
    """Keyword options as long options: ``w_fit=10`` is ``--w-fit 10``; True is a bare
    flag, False and None leave the option out; a list repeats the option."""
    arguments: list[str] = []
    for key, value in options.items():
        name = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            arguments.append(name)
        elif isinstance(value, (list, tuple)):
            for item in value:
                arguments += [name, os.fspath(item) if isinstance(item, os.PathLike) else str(item)]
        else:
            arguments += [name, os.fspath(value) if isinstance(value, os.PathLike) else str(value)]
    return arguments


def _read_json(path: str) -> dict | None:
    try:
        with open(path, encoding="utf-8") as file:
            return json.load(file)
    except FileNotFoundError:
        return None


def _read_mesh_if_present(path: str) -> tuple[np.ndarray, np.ndarray] | None:
    return read_mesh(path) if os.path.exists(path) else None


class _Folder:
    """`out` when given (created if missing), else a temporary folder removed on exit."""

    def __init__(self, out: str | os.PathLike | None):
        self._temporary = tempfile.TemporaryDirectory(prefix="garment-retarget-") if out is None else None
        self.path = self._temporary.name if self._temporary else os.fspath(out)

    def __enter__(self) -> str:
        return self.path

    def __exit__(self, *exc: object) -> None:
        if self._temporary:
            self._temporary.cleanup()


def _json_value(value: Any) -> Any:
    """A keyword's value as JSON: paths as text, sequences as arrays, NumPy scalars as numbers."""
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, (list, tuple)):
        return [_json_value(item) for item in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


def _typed(kind: Any, options: dict[str, Any]) -> Any:
    """`kind` (a typed options class) from keywords by long name, in one conversion."""
    keys = {key: _json_value(value) for key, value in options.items() if value is not None}
    return kind.from_json(json.dumps(keys))


def retarget_options(**options: Any) -> RetargetOptions:
    """Typed, checked ``retarget`` options from keywords by long name (``garment=``,
    ``source_skeleton=``, ``quality="fast"``, ``w_fit=10``, ``skirt=True``; None or False
    leaves one out). Each value goes through the command's own option and its checks;
    ``garment``, ``avatar`` and ``out`` are required. Raises ``UsageError`` naming the
    option."""
    return _typed(RetargetOptions, options)


def validate_options(**options: Any) -> ValidateOptions:
    """Typed, checked ``validate`` options from keywords by long name, as `retarget_options`
    makes them: ``garment`` and ``source`` take lists; ``garment`` and ``avatar`` are
    required. Raises ``UsageError`` naming the option."""
    return _typed(ValidateOptions, options)


def shrink_options(**options: Any) -> ShrinkOptions:
    """Typed, checked ``shrink`` options from keywords by long name, as `retarget_options`
    makes them; ``garment``, ``avatar`` and ``out`` are required. Raises ``UsageError``
    naming the option."""
    return _typed(ShrinkOptions, options)


def retarget(garment: Any, avatar: Any, out: str | os.PathLike | None = None, **options: Any) -> dict:
    """Refits `garment` onto `avatar` (``garment-retarget retarget``), in this process.

    Options are the command's long options by name (``source_skeleton=``, ``skirt=True``,
    ``quality="fast"``, ``w_fit=10``...), made into typed options by `retarget_options`;
    ``quiet`` defaults to True. Without `out` the outputs go to a temporary folder that is
    removed once read.

    Returns a dict: ``exit_code`` and ``status`` (certified, not_certified, no_valid_shrink,
    solver_failure, shape_changed or limit_reached), ``message``, ``report`` (report.json)
    and ``certificate`` (certificate.json) as dicts, ``garment`` as (V, F) arrays in the
    input OBJ's vertex order (None when nothing was written), and ``out`` (None for a
    temporary folder).

    A list of garments is an outfit, each garment a layer: the dict then has ``garments``,
    one (V, F) pair per garment written as OBJ (None for GLB), in the order given.
    """
    options.setdefault("quiet", True)
    outfit = isinstance(garment, list)
    with tempfile.TemporaryDirectory(prefix="garment-retarget-in-") as inputs, _Folder(out) as folder:
        garments = ([_mesh_file(g, inputs, f"garment{k}") for k, g in enumerate(garment)] if outfit
                    else _mesh_file(garment, inputs, "garment"))
        typed = retarget_options(garment=garments, avatar=_mesh_file(avatar, inputs, "avatar"), out=folder,
                                 **options)
        result = run_retarget(typed)
        report = _read_json(os.path.join(folder, "report.json"))
        found = {
            "exit_code": result.exit_code,
            "status": result.status_name,
            "message": result.message,
            "report": report,
            "certificate": _read_json(os.path.join(folder, "certificate.json")),
            "out": None if out is None else folder,
        }
        if outfit:
            layers = ((report or {}).get("outfit") or {}).get("layers", [])
            found["garments"] = [_read_mesh_if_present(layer["written"]) if layer["written"].endswith(".obj")
                                 else None for layer in layers]
        else:
            found["garment"] = _read_mesh_if_present(os.path.join(folder, "garment.obj"))
        return found


def validate(garments: Any, avatar: Any, sources: Iterable[Any] | None = None, **options: Any) -> dict:
    """Checks garments exactly against an avatar (``garment-retarget validate``), in this process.

    `garments` is one mesh or a list of them (layers); `sources`, one per garment, adds the
    shape check. Options: ``threshold=``, ``max_listed=``, ``report=``/``marks=``/``html=``
    (files to write) and the shape-check options, made into typed options by
    `validate_options`. Returns ``exit_code``, ``status`` (certified, not_certified or
    shape_changed), ``certified``, ``message`` (the command's summary line) and ``report``
    (the validation report as a dict).
    """
    if isinstance(garments, (str, os.PathLike)) or (
        isinstance(garments, tuple) and len(garments) == 2 and not isinstance(garments[0], (str, os.PathLike, tuple))
    ):
        garments = [garments]
    with tempfile.TemporaryDirectory(prefix="garment-retarget-validate-") as folder:
        typed = validate_options(
            garment=[_mesh_file(garment, folder, f"garment{g}") for g, garment in enumerate(garments)],
            avatar=_mesh_file(avatar, folder, "avatar"),
            source=[_mesh_file(source, folder, f"source{s}") for s, source in enumerate(sources or [])] or None,
            **options)
        result = run_validate(typed)
        return {"exit_code": result.exit_code, "status": result.status_name, "certified": result.certified,
                "message": result.summary, "report": result.report}


def shrink(garment: Any, avatar: Any, out: str | os.PathLike | None = None, **options: Any) -> dict:
    """Shrinks the avatar until it is certified free of the garment (``garment-retarget shrink``),
    in this process.

    Options: ``mode=``, ``voxel_size=``, skeletons and skin weights as in `retarget`, made
    into typed options by `shrink_options`; ``quiet`` defaults to True. Returns
    ``exit_code``, ``status`` (certified, no_valid_shrink or limit_reached), ``found``,
    ``message``, ``report`` (report.json), ``avatar``: the shrunk avatar as (V, F) arrays,
    None when none was found, and ``out`` (None for a temporary folder).
    """
    options.setdefault("quiet", True)
    with tempfile.TemporaryDirectory(prefix="garment-retarget-in-") as inputs, _Folder(out) as folder:
        typed = shrink_options(garment=_mesh_file(garment, inputs, "garment"),
                               avatar=_mesh_file(avatar, inputs, "avatar"), out=folder, **options)
        result = run_shrink(typed)
        return {
            "exit_code": result.exit_code,
            "status": result.status_name,
            "found": result.status == Outcome.certified,
            "message": result.message,
            "report": _read_json(os.path.join(folder, "report.json")),
            "avatar": _read_mesh_if_present(os.path.join(folder, "shrunk_avatar.obj")),
            "out": None if out is None else folder,
        }


def read_summary(out: str | os.PathLike) -> list[dict]:
    """The rows of OUT/summary.csv as dicts (strings, as written)."""
    with open(os.path.join(os.fspath(out), "summary.csv"), newline="", encoding="utf-8") as file:
        return list(csv.DictReader(file))


def batch(manifest: str | os.PathLike, out: str | os.PathLike, workers: int = 1, **options: Any) -> dict:
    """Runs a JSON Lines manifest (``garment-retarget batch``), one process per job.

    Options: ``threads_per_job=``, ``quiet=``. Jobs whose certified outputs exist for the
    same inputs and options are reused. Returns ``exit_code`` (0 when every job ended
    certified, 8 otherwise) and ``jobs``: the rows of OUT/summary.csv as dicts.
    """
    arguments = ["batch", os.fspath(manifest), "--out", os.fspath(out), "--workers", str(workers),
                 "--program", program_path()]
    exit_code = run_command(arguments + _option_arguments(options))
    return {"exit_code": exit_code, "jobs": read_summary(out)}
