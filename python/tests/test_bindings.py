import filecmp
import os

import numpy as np
import pytest

import garment_retarget as gr


def test_retarget_returns_reports_and_arrays(scene, tmp_path, batch_out):
    result = gr.retarget(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "run",
                         no_fit=scene / "no-fit.txt", quality="fast", threads=1)
    assert result["exit_code"] == 0
    assert result["status"] == "certified"
    assert result["certificate"]["certified"] is True
    assert result["report"]["quality"] == "fast"
    V, F = result["garment"]
    V_in, F_in = gr.read_mesh(scene / "garment.obj")
    assert V.shape == V_in.shape and V.dtype == np.float64
    np.testing.assert_array_equal(F, F_in)
    assert not np.array_equal(V, V_in)
    # The in-process run writes the same bytes as the batch's separate process.
    assert filecmp.cmp(tmp_path / "run" / "garment.obj", batch_out / "dress" / "garment.obj", shallow=False)


def test_retarget_takes_arrays_and_cleans_its_temporary_folder(scene):
    garment = gr.read_mesh(scene / "garment.obj")
    avatar = gr.read_mesh(scene / "avatar.obj")
    result = gr.retarget(garment, avatar, quality="fast", w_fit=0, shape_check="off")
    assert result["out"] is None
    assert result["status"] in ("certified", "shape_changed")
    assert result["report"]["parameters"]["w_fit"] == 0
    assert result["garment"][0].shape == garment[0].shape


def test_errors_are_exceptions_with_the_command_line_messages(scene, tmp_path):
    with pytest.raises(gr.InputError, match="missing.obj"):
        gr.retarget(tmp_path / "missing.obj", scene / "avatar.obj")
    with pytest.raises(gr.UsageError, match="fast, balanced|IsMember|quality"):
        gr.retarget(scene / "garment.obj", scene / "avatar.obj", quality="fastest")
    with pytest.raises(gr.UsageError, match="--no-such-option"):
        gr.retarget(scene / "garment.obj", scene / "avatar.obj", no_such_option=1)
    with pytest.raises(gr.InputError, match="out of range"):
        gr.retarget((np.zeros((3, 3)), np.array([[0, 1, 5]])), scene / "avatar.obj")
    with pytest.raises(TypeError):
        gr.retarget(42, scene / "avatar.obj")
    assert issubclass(gr.InputError, ValueError) and issubclass(gr.OutputError, OSError)


def test_typed_options_and_result(scene, tmp_path):
    options = gr.retarget_options(garment=scene / "garment.obj", avatar=scene / "avatar.obj",
                                  out=tmp_path / "typed", quality="fast", threads=np.int64(1),
                                  no_fit=scene / "no-fit.txt", skirt=False)
    assert isinstance(options, gr.RetargetOptions)
    assert options.quality == "fast" and options.threads == 1 and options.quiet is False
    assert options.garment == str(scene / "garment.obj")
    result = gr.run_retarget(options)
    assert isinstance(result, gr.RetargetResult)
    assert result.status == gr.Outcome.certified and result.exit_code == 0
    assert result.garment_path == str(tmp_path / "typed" / "garment.obj")
    assert result.message.startswith("certified")
    with pytest.raises(gr.UsageError, match="--out"):
        gr.retarget_options(garment=scene / "garment.obj", avatar=scene / "avatar.obj")


def test_knobs_are_checked_against_the_parameter_table_before_the_run(scene, tmp_path):
    knobs = {row["option"]: row for row in gr.parameters()}
    assert knobs["w_fit"]["name"] == "w_fit" and knobs["w_fit"]["type"] == "real"
    assert knobs["fit_samples"]["presets"] == {"fast": 1, "balanced": 3, "accurate": 6}
    assert knobs["pullback"]["name"] == "skeleton_pullback"
    with pytest.raises(gr.UsageError, match="--fit-samples: must be 1, 3 or 6"):
        gr.retarget(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "a", fit_samples=4)
    with pytest.raises(gr.UsageError, match="--max-al-rounds: must be a whole number"):
        gr.retarget(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "b", max_al_rounds=2.5)
    with pytest.raises(gr.UsageError, match="--dhat: not a number: thin"):
        gr.retarget(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "c", dhat="thin")
    with pytest.raises(gr.UsageError, match="--no-self-contact: a flag"):
        gr.retarget(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "d", no_self_contact=1)
    # Refused before anything ran: no folder was made.
    assert not any((tmp_path / name).exists() for name in "abcd")


def test_validate_reports_intersections(scene):
    intersecting = gr.validate(scene / "garment.obj", scene / "avatar.obj")
    assert intersecting["exit_code"] == 1
    assert intersecting["certified"] is False
    assert intersecting["report"]["counts"]["garment_avatar_intersections"] > 0


def test_shrink_returns_the_shrunk_avatar(scene):
    result = gr.shrink(scene / "garment.obj", scene / "avatar.obj", voxel_size=0.02)
    assert result["found"] is True
    V, F = result["avatar"]
    assert V.shape[1] == 3 and F.shape[1] == 3 and len(F) > 0
    assert gr.validate(scene / "garment.obj", result["avatar"])["certified"] is True


def test_batch_records_each_job_and_reuses_certified_ones(manifest, batch_out):
    jobs = {row["id"]: row for row in gr.read_summary(batch_out)}
    assert jobs["dress"]["status"] == "certified" and jobs["dress"]["certificate"] == "certified"
    assert jobs["broken"]["status"] == "bad_input" and "missing.obj" in jobs["broken"]["error"]
    before = os.stat(batch_out / "dress" / "garment.obj").st_mtime_ns
    again = gr.batch(manifest, batch_out, quiet=True)
    rows = {row["id"]: row for row in again["jobs"]}
    assert rows["dress"]["reused"] == "yes"
    assert os.stat(batch_out / "dress" / "garment.obj").st_mtime_ns == before


def test_a_timeout_ends_the_call_with_its_status_and_no_result(scene, tmp_path):
    result = gr.retarget(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "late",
                         no_fit=scene / "no-fit.txt", timeout=0.05)
    assert result["exit_code"] == 9
    assert result["status"] == "limit_reached"
    assert not (tmp_path / "late").exists()


def test_ctrl_c_stops_a_running_call_and_raises_keyboard_interrupt(scene, tmp_path):
    import signal
    import threading

    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            gr.retarget(scene / "garment.obj", scene / "avatar.obj", out=tmp_path / "stopped",
                        no_fit=scene / "no-fit.txt", quality="accurate", threads=1)
    finally:
        timer.cancel()
    assert not (tmp_path / "stopped").exists()
    # Python's own handler is back: the next Ctrl-C raises in Python as usual.
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def _open_cylinder(radius, z0, z1, rings=12, segments=32):
    """A tube about the z axis, faces outward (core/mesh/primitives.cpp's open_cylinder)."""
    angle = 2 * np.pi * np.arange(segments) / segments
    z = np.linspace(z0, z1, rings)
    V = np.array([[radius * np.cos(a), radius * np.sin(a), h] for h in z for a in angle])
    F = []
    for i in range(rings - 1):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            F += [[a, b, b + segments], [a, b + segments, a + segments]]
    return V, np.array(F)


def _capsule(radius, half_length, rings=24, segments=32):
    """A closed sphere stretched to `half_length` along z, faces outward."""
    V = [[0.0, 0.0, -half_length]]
    for i in range(1, rings):
        polar = np.pi * i / rings
        for j in range(segments):
            a = 2 * np.pi * j / segments
            V.append([radius * np.sin(polar) * np.cos(a), radius * np.sin(polar) * np.sin(a),
                      -half_length * np.cos(polar)])
    V.append([0.0, 0.0, half_length])
    top = len(V) - 1
    ring = lambda i, j: 1 + (i - 1) * segments + j % segments  # noqa: E731
    F = [[0, ring(1, j + 1), ring(1, j)] for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            F += [[ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)], [ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)]]
    F += [[top, ring(rings - 1, j), ring(rings - 1, j + 1)] for j in range(segments)]
    return np.array(V), np.array(F)


def test_retarget_takes_a_list_of_garments_as_an_outfit(tmp_path):
    # Two sleeves nested on a capsule, refitted onto a fatter one (as test_outfit_retarget.cpp).
    gr.write_mesh(tmp_path / "inner.obj", *_open_cylinder(0.32, -0.5, 0.5))
    gr.write_mesh(tmp_path / "outer.obj", *_open_cylinder(0.35, -0.5, 0.5))
    gr.write_mesh(tmp_path / "source_body.obj", *_capsule(0.3, 1.2))
    avatar = _capsule(0.31, 1.2)
    result = gr.retarget([tmp_path / "outer.obj", tmp_path / "inner.obj"], avatar, out=tmp_path / "run",
                         source_body=tmp_path / "source_body.obj", quality="fast", threads=1,
                         voxel_size=0.05, max_newton_iterations=300)
    assert result["exit_code"] == 0, result["message"]
    assert result["status"] == "certified"
    assert result["certificate"]["certified"] is True
    outfit = result["report"]["outfit"]
    assert [layer["name"] for layer in outfit["layers"]] == ["outer", "inner"]
    assert outfit["order"] == ["inner", "outer"] and outfit["order_from"] == "measured"
    assert outfit["order_kept"] is True and outfit["layer_intersections"] == 0
    assert "garment" not in result
    assert len(result["garments"]) == 2
    for (V, F), name in zip(result["garments"], ["outer", "inner"]):
        V_in, F_in = gr.read_mesh(tmp_path / f"{name}.obj")
        assert V.shape == V_in.shape
        np.testing.assert_array_equal(F, F_in)
        assert not np.array_equal(V, V_in)
    # In the order given: the outer sleeve is still outside the inner one.
    radius = [np.median(np.hypot(V[:, 0], V[:, 1])) for V, _ in result["garments"]]
    assert radius[0] > radius[1] > 0.31
    assert (tmp_path / "run" / "outer.obj").exists() and (tmp_path / "run" / "inner.obj").exists()


def test_formats_come_from_the_registry_and_check_format(scene, tmp_path):
    formats = gr.formats()
    names = [f["name"] for f in formats]
    assert "obj" in names and "glb" in names
    assert all(f["extensions"] and f["extensions"][0].startswith(".") for f in formats)
    common = dict(garment=scene / "garment.obj", avatar=scene / "avatar.obj", out=tmp_path / "f")
    assert gr.retarget_options(**common).format is None
    for name in names:
        assert gr.retarget_options(**common, format=name).format == name
    with pytest.raises(gr.UsageError, match="--format"):
        gr.retarget_options(**common, format="stl")
