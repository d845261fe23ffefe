"""The tests read nothing of the source tree but the bundled scene, two folders up from here:
copied with them (python/tests and scenes/dress_form), they test an installed wheel
(tools/check_wheel.sh does so on a bare Debian 12)."""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "dress_form"


def pytest_report_header(config):
    import garment_retarget

    return f"garment_retarget: {Path(garment_retarget.__file__).parent}"


@pytest.fixture(scope="session")
def scene() -> Path:
    """The bundled dress-form scene (garment.obj, avatar.obj, no-fit.txt)."""
    return SCENE


@pytest.fixture(scope="session")
def manifest(tmp_path_factory) -> Path:
    """A manifest of the bundled scene (fast preset) and one job whose garment is missing."""
    folder = tmp_path_factory.mktemp("manifest")
    lines = [
        f'{{"id": "dress", "garment": "{SCENE}/garment.obj", "avatar": "{SCENE}/avatar.obj", '
        f'"no_fit": "{SCENE}/no-fit.txt", "quality": "fast"}}',
        f'{{"id": "broken", "garment": "missing.obj", "avatar": "{SCENE}/avatar.obj"}}',
    ]
    path = folder / "manifest.jsonl"
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture(scope="session")
def batch_out(manifest, tmp_path_factory) -> Path:
    """The manifest run once by the local batch."""
    import garment_retarget as gr

    out = tmp_path_factory.mktemp("batch") / "out"
    result = gr.batch(manifest, out, workers=2, quiet=True)
    assert result["exit_code"] == 8
    return out
