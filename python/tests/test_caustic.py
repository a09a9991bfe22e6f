"""The Python package against the renderer: shapes and dtypes, determinism, Mitsuba's Cornell box
reference (statistically, as tests/tests/reference.rs), errors naming file and line, the GIL released
while rendering, Ctrl-C, and the kept backend. Run by ./run-tests after the cargo tests; small images
throughout (the scenes' `res` parameter), so that the suite takes seconds on the CPU backend."""

import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import caustic

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORNELL = ROOT / "scenes" / "cornell-box.xml"
# The shared reference data beside the repository (CAUSTIC_SHARED overrides), as the Rust tests find it.
SHARED = pathlib.Path(os.environ.get("CAUSTIC_SHARED", ROOT.parent / "shared"))
CBOX = SHARED / "scenes" / "mitsuba" / "scenes" / "cbox" / "cbox.xml"
CBOX_REFERENCE = SHARED / "refs" / "mitsuba" / "cbox.exr"
CBOX_REFERENCE_SPP = 2048

needs_shared = pytest.mark.skipif(
    not CBOX_REFERENCE.is_file(), reason=f"{SHARED} has no Mitsuba references (set CAUSTIC_SHARED)"
)


@pytest.fixture(scope="module")
def small():
    return caustic.load_file(CORNELL, res=32)


def test_render_gives_a_finite_float32_image(small):
    assert (small.width, small.height) == (32, 32)
    image = small.render(spp=4, backend="cpu", progress=False)
    assert image.shape == (32, 32, 3) and image.dtype == np.float32
    assert np.isfinite(image).all() and image.mean() > 0.0


def caustic_binary():
    """The command line built beside this package (./run-tests' cargo tests build it), if it is."""
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    binary = target / "release" / "caustic"
    return binary if binary.is_file() else None


@pytest.mark.skipif(caustic_binary() is None, reason="no target/release/caustic (cargo build --release)")
def test_the_image_is_the_command_lines(tmp_path, small):
    """One library under both: the same scene, seed and samples give the command line's image, bit
    for bit (CPU)."""
    output = tmp_path / "cli.exr"
    subprocess.run(
        [caustic_binary(), "render", CORNELL, "-D", "res=32", "--spp", "4", "--seed", "3",
         "--backend", "cpu", "-q", "-o", output],
        check=True,
    )
    image = small.render(spp=4, seed=3, backend="cpu", progress=False)
    np.testing.assert_array_equal(image, caustic.read(output))


def test_the_same_seed_gives_the_same_image_and_another_seed_another(small):
    a = small.render(spp=4, seed=3, backend="cpu", progress=False)
    b = small.render(spp=4, seed=3, backend="cpu", progress=False)
    c = small.render(spp=4, seed=4, backend="cpu", progress=False)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_a_kept_backend_renders_as_a_new_one():
    """The second render runs on the first one's backend (its accumulation cleared): the image
    must be the one a fresh scene gives, whatever ran before it."""
    kept = caustic.load_file(CORNELL, res=16)
    kept.render(spp=8, seed=1, backend="cpu", progress=False)
    again = kept.render(spp=2, seed=5, backend="cpu", progress=False)
    fresh = caustic.load_file(CORNELL, res=16).render(spp=2, seed=5, backend="cpu", progress=False)
    np.testing.assert_array_equal(again, fresh)


def test_params_are_the_command_lines_defines():
    scene = caustic.load_file(CORNELL, res=24, spp=9)
    assert (scene.width, scene.height, scene.spp) == (24, 24, 9)
    assert scene.render(backend="cpu", progress=False).shape == (24, 24, 3)


def test_variance_and_integrator_and_film(small):
    image, variance = small.render(spp=4, backend="cpu", integrator="direct", film="fis", variance=True, progress=False)
    assert variance.shape == image.shape and variance.dtype == np.float64
    assert (variance >= 0).all() and variance.max() > 0


def test_aovs_come_by_name():
    scene = caustic.load_file(ROOT / "tests" / "data" / "aov.xml", aovs="dd.y:depth,nn:sh_normal")
    image, aovs = scene.render(spp=2, backend="cpu", aovs=True, progress=False)
    assert image.shape == (48, 64, 3)
    # The EXR channel names `render --output x.exr` writes (the nested integrator's image among them).
    assert {"dd.y.T", "nn.X", "nn.Y", "nn.Z", "my_image.R"} <= set(aovs)
    assert all(a.shape == (48, 64) and a.dtype == np.float32 for a in aovs.values())
    assert aovs["dd.y.T"].max() > 0


def test_bad_arguments_raise_value_errors(small):
    for kwargs in [{"backend": "xpu"}, {"integrator": "mlt"}, {"film": "box"}, {"gpus": "none"}]:
        with pytest.raises(ValueError):
            small.render(spp=1, progress=False, **kwargs)


def test_a_bad_scene_raises_with_its_file_and_line(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text(
        textwrap.dedent(
            """\
            <scene version="3.0.0">
                <sensor type="perspective">
                    <float name="fov" value="wide"/>
                </sensor>
            </scene>
            """
        )
    )
    with pytest.raises(caustic.CausticError) as error:
        caustic.load_file(bad)
    assert f"{bad}:3" in str(error.value) and "fov" in str(error.value)
    with pytest.raises(caustic.CausticError, match="no-such-scene.xml"):
        caustic.load_file(tmp_path / "no-such-scene.xml")


def test_write_and_read_back(tmp_path, small):
    image = small.render(spp=2, backend="cpu", progress=False)
    caustic.write(tmp_path / "out.exr", image)
    np.testing.assert_array_equal(caustic.read(tmp_path / "out.exr"), image)
    caustic.write(tmp_path / "out.png", image)
    assert (tmp_path / "out.png").read_bytes()[:4] == b"\x89PNG"
    with pytest.raises(ValueError):
        caustic.write(tmp_path / "flat.exr", image[:, :, 0])
    with pytest.raises(caustic.CausticError, match="unknown image format"):
        caustic.write(tmp_path / "out.tiff", image)


def test_write_refuses_to_overwrite_an_input(tmp_path, small):
    """The command line's guard: no output may be a file this process has read."""
    image = small.render(spp=1, backend="cpu", progress=False)
    texture = tmp_path / "input.exr"
    caustic.write(texture, image)
    caustic.read(texture)
    with pytest.raises(caustic.CausticError, match="refusing to write .*input.exr"):
        caustic.write(texture, np.zeros_like(image))
    np.testing.assert_array_equal(caustic.read(texture), image)


@needs_shared
def test_cbox_matches_mitsuba():
    """As tests/tests/reference.rs: at least 99% of the pixels pass the z-test and the mean
    luminance agrees within 4 standard errors; the same statistics catch a 3% brighter image."""
    scene = caustic.load_file(CBOX)
    spp = 16
    image, variance = scene.render(spp=spp, seed=7, backend="cpu", variance=True, progress=False)
    reference = caustic.read(CBOX_REFERENCE)

    def stats(img, var):
        return caustic.compare(
            img,
            reference,
            variance=var,
            image_spp=spp,
            reference_spp=CBOX_REFERENCE_SPP,
            sum_variance_factor=scene.sum_variance_factor,
        )

    c = stats(image, variance)
    print({k: v for k, v in c.items() if k != "error_map"})
    assert c["pass_fraction"] >= 0.99, c["pass_fraction"]
    assert abs(c["luminance_z"]) < 4.0, c["luminance_z"]
    assert abs(c["luminance_ratio"] - 1.0) < 0.02
    assert c["error_map"].shape == (256, 256)
    brighter = stats(image * 1.03, variance * 1.03**2)
    assert brighter["pass_fraction"] < 0.99 or abs(brighter["luminance_z"]) >= 4.0
    # Without a variance: the plain statistics only.
    plain = caustic.compare(image, reference)
    assert plain["pass_fraction"] is None and plain["luminance_z"] is None
    assert plain["rmse"] == pytest.approx(c["rmse"])


@needs_shared
def test_compare_reads_files_as_the_command_line(tmp_path):
    image = caustic.read(CBOX_REFERENCE)
    c = caustic.compare(CBOX_REFERENCE, image)
    assert c["rmse"] == 0.0 and c["luminance_ratio"] == pytest.approx(1.0)
    with pytest.raises(caustic.CausticError, match="image is 8×8 but the reference is 256×256"):
        caustic.compare(np.zeros((8, 8, 3)), CBOX_REFERENCE)


def test_another_thread_runs_during_a_render():
    """The GIL is released while rendering: this thread keeps running Python while another thread
    renders. With the GIL held it would stand still for the whole render."""
    scene = caustic.load_file(CORNELL, res=64)
    # A render of about a second on this machine, whatever its speed.
    start = time.perf_counter()
    scene.render(spp=4, backend="cpu", progress=False)
    spp = max(4, round(4 / (time.perf_counter() - start)))
    done = {}

    def render():
        start = time.perf_counter()
        scene.render(spp=spp, backend="cpu", progress=False)
        done["seconds"] = time.perf_counter() - start

    worker = threading.Thread(target=render)
    last, longest, ticks = time.perf_counter(), 0.0, 0
    worker.start()
    while worker.is_alive():
        now = time.perf_counter()
        longest, last, ticks = max(longest, now - last), now, ticks + 1
    worker.join()
    print(f"{spp} spp in {done['seconds']:.2f} s, {ticks} ticks here meanwhile, longest pause {longest * 1e3:.0f} ms")
    assert longest < done["seconds"] / 2


def test_threads_share_a_scene():
    """Two threads rendering one scene take turns (its backend is locked for a render), and this
    thread's reading of the scene meanwhile does not wait on them holding the GIL (which their
    renders take between passes to look for Ctrl-C)."""
    scene = caustic.load_file(CORNELL, res=32)
    expected = scene.render(spp=16, seed=2, backend="cpu", progress=False)
    images = []
    workers = [
        threading.Thread(
            target=lambda: images.append(scene.render(spp=16, seed=2, backend="cpu", progress=False)), daemon=True
        )
        for _ in range(2)
    ]
    for w in workers:
        w.start()
    while any(w.is_alive() for w in workers):
        assert scene.sum_variance_factor >= 1.0
    for w in workers:
        w.join(timeout=60)
    assert len(images) == 2
    for image in images:
        np.testing.assert_array_equal(image, expected)


def test_ctrl_c_stops_a_render_and_leaves_the_scene_usable():
    """A real SIGINT to a Python process rendering for minutes: KeyboardInterrupt within about a
    pass, and the scene renders again afterwards."""
    script = textwrap.dedent(
        f"""\
        import signal, sys, time, caustic
        # Python leaves SIGINT ignored where it started ignored (a shell's background job, as a CI
        # runner may start this suite): what is tested is caustic's handling, not that.
        signal.signal(signal.SIGINT, signal.default_int_handler)
        scene = caustic.load_file({str(CORNELL)!r}, res=64)
        print("rendering", flush=True)
        start = time.perf_counter()
        try:
            scene.render(spp=1_000_000, backend="cpu", progress=False)
            print("finished", flush=True)
        except KeyboardInterrupt:
            print(f"interrupted after {{time.perf_counter() - start:.2f}} s", flush=True)
        print("again", scene.render(spp=1, backend="cpu", progress=False).shape, flush=True)
        """
    )
    process = subprocess.Popen(
        [sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        assert process.stdout.readline().strip() == "rendering"
        time.sleep(1.0)
        signalled = time.perf_counter()
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=60)
    finally:
        process.kill()
    latency = time.perf_counter() - signalled
    print(out, err, f"exited {latency:.2f} s after the signal")
    assert "interrupted after" in out, err
    assert "again (64, 64, 3)" in out, err
    assert process.returncode == 0
    # A pass lasts about a second (render::TARGET_PASS).
    assert latency < 10


def test_gpu_agrees_with_the_cpu_and_keeps_its_pipelines():
    """On the GPU backend (lavapipe where there is no GPU): the same image statistics as the CPU's.
    The second render runs on the kept backend, without building buffers or pipelines (timings
    printed: on lavapipe with a cold shader cache, 14 s against 0.05 s)."""
    scene = caustic.load_file(CORNELL, res=32)
    seconds = []
    for _ in range(2):
        start = time.perf_counter()
        try:
            scene.render(spp=4, backend="gpu", progress=False)
        except caustic.CausticError as e:
            if "no Vulkan adapter" in str(e):
                pytest.skip(str(e))
            raise
        seconds.append(time.perf_counter() - start)
    print(f"first render {seconds[0]:.2f} s (buffers, backend, pipelines), second {seconds[1]:.2f} s")
    gpu, variance = scene.render(spp=64, backend="gpu", variance=True, progress=False)
    factor = scene.sum_variance_factor
    cpu = scene.render(spp=64, seed=1, backend="cpu", progress=False)
    # Two renders of 64 spp each: samples_ratio 1 counts the CPU image's noise.
    c = caustic.compare(gpu, cpu, variance=variance, image_spp=64, reference_spp=64, sum_variance_factor=factor)
    print({k: v for k, v in c.items() if k != "error_map"})
    assert c["pass_fraction"] >= 0.99 and abs(c["luminance_z"]) < 4.0
