"""Scene.convergence: the command line's `caustic convergence` curve as numpy arrays, measured by the same
library function (convergence::measure_warmed_up). On a tiny Cornell box and the CPU backend."""

import csv
import os
import pathlib
import subprocess

import numpy as np
import pytest

import caustic

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORNELL = ROOT / "scenes" / "cornell-box.xml"
KEYS = ("spp", "seconds", "rmse", "rel_mse", "luminance_ratio")


@pytest.fixture(scope="module")
def tiny():
    scene = caustic.load_file(CORNELL, res=16)
    reference = scene.render(spp=1024, seed=100, backend="cpu", progress=False)
    return scene, reference


def test_the_curve_comes_as_arrays(tiny):
    scene, reference = tiny
    curve = scene.convergence(reference, spp=64, backend="cpu")
    assert set(curve) == set(KEYS) | {"backend", "log_log_slope"}
    np.testing.assert_array_equal(curve["spp"], [1, 2, 4, 8, 16, 32, 64])
    assert curve["spp"].dtype == np.int64
    for key in KEYS[1:]:
        assert curve[key].shape == (7,) and curve[key].dtype == np.float64, key
        assert np.isfinite(curve[key]).all(), key
    assert (np.diff(curve["spp"]) > 0).all()
    assert (curve["seconds"] > 0).all() and (np.diff(curve["seconds"]) >= 0).all()
    assert (curve["rmse"] > 0).all() and (curve["rel_mse"] > 0).all()
    # 64 times the samples: the error falls (RMSE by about 8; measured 6 to 12 over seeds), and the
    # image is as bright as the reference (measured within 3%).
    assert curve["rmse"][-1] < curve["rmse"][0] / 2
    assert abs(curve["luminance_ratio"][-1] - 1.0) < 0.1
    assert isinstance(curve["backend"], str) and curve["backend"].startswith("cpu")
    assert -3.0 < curve["log_log_slope"] < 0.0  # about -1


def test_the_last_point_is_the_budget_and_the_seed_decides(tiny):
    scene, reference = tiny
    a = scene.convergence(reference, spp=6, seed=4, backend="cpu")
    b = scene.convergence(reference, spp=6, seed=4, backend="cpu")
    c = scene.convergence(reference, spp=6, seed=5, backend="cpu")
    np.testing.assert_array_equal(a["spp"], [1, 2, 4, 6])
    np.testing.assert_array_equal(a["rmse"], b["rmse"])
    assert not np.array_equal(a["rmse"], c["rmse"])
    # The scene's own count by default (sample_count 64 of cornell-box.xml, with res=16).
    assert scene.convergence(reference, backend="cpu", integrator="direct", film="fis")["spp"][-1] == scene.spp


def test_a_reference_file_is_read_as_the_command_line_reads_it(tiny, tmp_path):
    scene, reference = tiny
    path = tmp_path / "reference.exr"
    caustic.write(path, reference)
    from_array = scene.convergence(reference, spp=4, backend="cpu")
    from_file = scene.convergence(path, spp=4, backend="cpu")
    np.testing.assert_array_equal(from_array["rmse"], from_file["rmse"])


def test_a_reference_file_with_its_variance_gives_the_net_error(tiny, tmp_path):
    """Its variance beside it (as `render --variance` writes it): the curve also says the error with
    the reference's noise taken out, below the raw error at every point."""
    scene, _ = tiny
    image, variance = scene.render(spp=16, seed=7, backend="cpu", progress=False, variance=True)
    caustic.write(tmp_path / "noisy.exr", image)
    caustic.write(tmp_path / "noisy.variance.exr", variance)
    curve = scene.convergence(tmp_path / "noisy.exr", spp=16, backend="cpu")
    for key in ("net_mse", "net_rel_mse"):
        assert curve[key].shape == curve["rmse"].shape and np.isfinite(curve[key]).all(), key
    assert (curve["net_mse"] < curve["rmse"] ** 2).all()
    assert (curve["net_rel_mse"] < curve["rel_mse"]).all()
    assert "net_mse" not in scene.convergence(image, spp=2, backend="cpu")


def test_a_reference_of_another_size_is_refused(tiny, tmp_path):
    scene, _ = tiny
    with pytest.raises(caustic.CausticError, match=r"reference is 8×8 but .*cornell-box.xml renders 16×16"):
        scene.convergence(np.ones((8, 8, 3), np.float32), spp=2, backend="cpu")
    with pytest.raises(caustic.CausticError, match="not finite"):
        scene.convergence(np.full((16, 16, 3), np.nan, np.float32), spp=2, backend="cpu")
    with pytest.raises(ValueError):
        scene.convergence(np.ones((16, 16, 3), np.float32), spp=2, backend="xpu")


def test_a_dict_scene_has_a_curve_too(tiny):
    _, reference = tiny
    scene = caustic.load_dict(
        {
            "type": "scene",
            "sensor": {"type": "perspective", "film": {"type": "hdrfilm", "width": 16, "height": 16}},
            "ball": {"type": "sphere", "center": [0.0, 0.0, 5.0]},
            "sky": {"type": "constant"},
        }
    )
    curve = scene.convergence(reference, spp=2, backend="cpu")
    np.testing.assert_array_equal(curve["spp"], [1, 2])


def caustic_binary():
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    binary = target / "release" / "caustic"
    return binary if binary.is_file() else None


@pytest.mark.skipif(caustic_binary() is None, reason="no target/release/caustic (cargo build --release)")
def test_the_curve_is_the_command_lines(tiny, tmp_path):
    """The same scene, reference, budget and seed: the command line's errors (its CSV's digits)."""
    scene, reference = tiny
    caustic.write(tmp_path / "reference.exr", reference)
    subprocess.run(
        [caustic_binary(), "convergence", CORNELL, tmp_path / "reference.exr", "-D", "res=16", "--spp", "8",
         "--seed", "2", "--backend", "cpu", "--csv", tmp_path / "curve.csv"],
        check=True, stdout=subprocess.DEVNULL,
    )
    with open(tmp_path / "curve.csv") as f:
        rows = list(csv.DictReader(f))
    curve = scene.convergence(reference, spp=8, seed=2, backend="cpu")
    np.testing.assert_array_equal(curve["spp"], [int(r["spp"]) for r in rows])
    for key in ("rmse", "rel_mse", "luminance_ratio"):
        np.testing.assert_allclose(curve[key], [float(r[key]) for r in rows], rtol=1e-6, err_msg=key)
