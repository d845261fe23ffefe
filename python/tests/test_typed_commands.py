"""validate() and shrink() run on typed options in the process: the same results as the
command line's, and options refused by name before anything runs."""

import filecmp
import json
import subprocess

import pytest

import garment_retarget as gr


def _command_line(*arguments):
    """Runs the program (a separate process); returns its exit code and stdout."""
    done = subprocess.run([gr.program_path(), *map(str, arguments)], capture_output=True, text=True)
    return done.returncode, done.stdout


def _without_times(value):
    """`value` without the keys that hold times, which differ from run to run."""
    if isinstance(value, dict):
        return {k: _without_times(v) for k, v in value.items() if not k.endswith("seconds")}
    if isinstance(value, list):
        return [_without_times(v) for v in value]
    return value


def test_validate_equals_the_command_line(scene, tmp_path):
    garment, avatar = scene / "garment.obj", scene / "avatar.obj"
    exit_code, stdout = _command_line("validate", "--garment", garment, "--avatar", avatar,
                                      "--report", tmp_path / "cli.json", "--max-listed", 5)
    result = gr.validate(garment, avatar, max_listed=5)
    assert exit_code == result["exit_code"] == 1
    assert result["status"] == "not_certified" and result["certified"] is False
    assert result["message"] == stdout.strip()
    assert result["report"] == json.loads((tmp_path / "cli.json").read_text())
    assert result["report"]["parameters"]["max_listed"] == 5 and result["report"]["issues"]["truncated"] is True


def test_shrink_equals_the_command_line_and_validate_checks_its_avatar(scene, tmp_path):
    garment, avatar = scene / "garment.obj", scene / "avatar.obj"
    exit_code, stdout = _command_line("shrink", "--garment", garment, "--avatar", avatar,
                                      "--out", tmp_path / "cli", "--voxel-size", 0.02, "--quiet")
    result = gr.shrink(garment, avatar, out=tmp_path / "py", voxel_size=0.02)
    assert exit_code == result["exit_code"] == 0
    assert result["status"] == "certified" and result["found"] is True
    assert stdout.splitlines()[0] == result["message"]
    assert _without_times(result["report"]) == _without_times(
        json.loads((tmp_path / "cli" / "report.json").read_text()))
    assert filecmp.cmp(tmp_path / "cli" / "shrunk_avatar.obj", tmp_path / "py" / "shrunk_avatar.obj",
                       shallow=False)
    assert result["out"] == str(tmp_path / "py")

    # The garment against the shrunk avatar, with itself as its source: certified, shape kept.
    shrunk = tmp_path / "py" / "shrunk_avatar.obj"
    exit_code, stdout = _command_line("validate", "--garment", garment, "--avatar", shrunk,
                                      "--source", garment, "--report", tmp_path / "cli.json")
    checked = gr.validate(garment, shrunk, sources=[garment])
    assert exit_code == checked["exit_code"] == 0
    assert checked["status"] == "certified" and checked["certified"] is True
    assert checked["message"] == stdout.strip()
    assert checked["report"] == json.loads((tmp_path / "cli.json").read_text())
    assert checked["report"]["garments"][0]["shape"]["source"]["path"] == str(garment)


def test_typed_validate_and_shrink_options(scene, tmp_path):
    options = gr.validate_options(garment=[scene / "garment.obj"], avatar=scene / "avatar.obj",
                                  threshold=0.01, source=[scene / "garment.obj"])
    assert isinstance(options, gr.ValidateOptions)
    assert options.garments == [str(scene / "garment.obj")] and options.threshold == 0.01
    assert options.sources == [str(scene / "garment.obj")] and options.max_listed == 100
    result = gr.run_validate(options)
    assert isinstance(result, gr.ValidateResult)
    assert result.status == gr.Outcome.not_certified and result.exit_code == 1

    shrink = gr.shrink_options(garment=scene / "garment.obj", avatar=scene / "avatar.obj",
                               out=tmp_path / "s", mode="skeleton", voxel_size=0.05, quiet=True)
    assert isinstance(shrink, gr.ShrinkOptions)
    assert shrink.mode == "skeleton" and shrink.voxel_size == 0.05 and shrink.quiet is True
    assert shrink.out_dir == str(tmp_path / "s")
    assert gr.shrink_options(garment="g.obj", avatar="a.obj", out="o").quiet is False


@pytest.mark.parametrize("options, named", [
    (dict(no_such_option=1), "--no-such-option: not a validate option"),
    (dict(threshold="near"), "--threshold"),
    (dict(threshold=-1), "--threshold"),
    (dict(max_listed=2.5), "--max-listed"),
    (dict(shape_check="maybe"), "--shape-check"),
    (dict(report=True), "--report: needs a number or a text"),
])
def test_validate_refuses_an_unknown_or_mistyped_option_by_name(scene, options, named):
    with pytest.raises(gr.UsageError, match=named):
        gr.validate(scene / "garment.obj", scene / "avatar.obj", **options)


@pytest.mark.parametrize("options, named", [
    (dict(no_such_option=1), "--no-such-option: not a shrink option"),
    (dict(w_fit=10), "--w-fit: not a shrink option"),
    (dict(voxel_size=-1), "--voxel-size"),
    (dict(voxel_size="fine"), "--voxel-size"),
    (dict(mode="melt"), "--mode"),
    (dict(quiet=1), "--quiet: a flag"),
])
def test_shrink_refuses_an_unknown_or_mistyped_option_by_name(scene, tmp_path, options, named):
    with pytest.raises(gr.UsageError, match=named):
        gr.shrink(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "out", **options)
    # Refused before anything ran: no folder was made.
    assert not (tmp_path / "out").exists()


def test_bad_input_files_raise_as_the_command_line_ends(scene, tmp_path):
    with pytest.raises(gr.InputError, match="missing.obj"):
        gr.validate(tmp_path / "missing.obj", scene / "avatar.obj")
    with pytest.raises(gr.InputError, match="1 --source files for 2 --garment files"):
        gr.validate([scene / "garment.obj", scene / "garment.obj"], scene / "avatar.obj",
                    sources=[scene / "garment.obj"])
    with pytest.raises(gr.InputError, match="missing.obj"):
        gr.shrink(tmp_path / "missing.obj", scene / "avatar.obj")


def test_ctrl_c_stops_a_running_shrink_and_a_timeout_ends_it_with_its_status(scene, tmp_path):
    import os
    import signal
    import threading

    garment, avatar = scene / "garment.obj", scene / "avatar.obj"
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            gr.shrink(garment, avatar, out=tmp_path / "stopped", voxel_size=0.004)
    finally:
        timer.cancel()
    assert not (tmp_path / "stopped").exists()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler

    late = gr.shrink(garment, avatar, out=tmp_path / "late", voxel_size=0.004, timeout=0.2)
    assert late["exit_code"] == 9 and late["status"] == "limit_reached" and late["found"] is False
    assert "--timeout" in late["message"] and late["report"] is None
    assert late["avatar"] is None
