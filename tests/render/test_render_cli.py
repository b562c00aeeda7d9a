"""bras-kit render: default outputs, overwrite protection, every output kind, clean errors."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

SMALL = ("--size", "96x72")


def gif_info(path):
    from PIL import Image

    with Image.open(path) as image:
        delays = []
        for index in range(image.n_frames):
            image.seek(index)
            delays.append(image.info["duration"])
        return image.size, delays


@pytest.mark.slow
def test_gif_alone_writes_the_tutorial_motion_as_bras_gif_here(run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli("render", "--gif")
    assert code == 0
    assert os.listdir(tmp_path) == ["bras.gif"]
    assert "wrote bras.gif in the current folder" in err
    assert "200 frames at 20 fps (10 s)" in err and "tutorial" in err
    size, delays = gif_info(tmp_path / "bras.gif")
    assert size == (640, 480)
    assert len(delays) == 200 and set(delays) == {50}
    assert "rendering [" not in err  # piped: no progress bar


def test_no_output_option_writes_the_pose_as_bras_png(run_cli, tmp_path, monkeypatch):
    from PIL import Image

    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli("render", *SMALL)
    assert code == 0
    assert "wrote bras.png in the current folder" in err and "zero pose" in err
    assert Image.open(tmp_path / "bras.png").size == (96, 72)


def test_existing_output_is_not_overwritten_without_force(run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bras.png").write_bytes(b"mine")
    code, _, err = run_cli("render", *SMALL)
    assert code == 2
    assert "bras.png already exists" in err and "--force" in err
    assert (tmp_path / "bras.png").read_bytes() == b"mine"
    assert "Traceback" not in err
    code, _, _ = run_cli("render", *SMALL, "--force")
    assert code == 0
    assert (tmp_path / "bras.png").read_bytes()[:4] == b"\x89PNG"


def test_existing_gif_is_refused_before_any_rendering(run_cli, tmp_path):
    target = tmp_path / "anim.gif"
    target.write_bytes(b"old")
    code, _, err = run_cli("render", "--gif", str(target), *SMALL, "--duration", "1")
    assert code == 2 and "already exists" in err
    assert target.read_bytes() == b"old"


def test_frame_count_is_duration_times_fps(run_cli, tmp_path):
    path = tmp_path / "anim.gif"
    code, _, err = run_cli("render", "--gif", str(path), *SMALL, "--duration", "1.5", "--fps", "10")
    assert code == 0, err
    _, delays = gif_info(path)
    assert len(delays) == 15 and set(delays) == {100}


def test_every_output_at_once(run_cli, tmp_path):
    from PIL import Image

    gif, mp4, png, folder = tmp_path / "a.gif", tmp_path / "a.mp4", tmp_path / "first.png", tmp_path / "frames"
    code, _, err = run_cli("render", *SMALL, "--duration", "1", "--fps", "8", "--gif", str(gif), "--mp4", str(mp4),
                           "--frames-dir", str(folder), "-o", str(png), "--view", "front", "--tf")
    assert code == 0, err
    assert sorted(os.listdir(folder)) == [f"frame_{i:04d}.png" for i in range(8)]
    assert len(gif_info(gif)[1]) == 8
    import imageio

    with imageio.get_reader(mp4, format="FFMPEG") as reader:
        assert sum(1 for _ in reader) == 8
    # -o holds the first frame of the animation
    assert np.array_equal(np.asarray(Image.open(png)), np.asarray(Image.open(folder / "frame_0000.png")))
    code, _, err = run_cli("render", *SMALL, "--duration", "1", "--fps", "8", "--frames-dir", str(folder))
    assert code == 2 and "frame_*.png" in err


def test_software_backend_from_the_command_line(run_cli, tmp_path):
    from PIL import Image

    path = tmp_path / "pose.png"
    code, _, err = run_cli("render", "--backend", "software", "--set", "epaule=0.8", "-o", str(path), *SMALL)
    assert code == 0, err
    assert "software" in err and "epaule=0.8" in err
    image = np.asarray(Image.open(path))
    assert image.shape == (72, 96, 3)
    assert (image.sum(axis=2) < 600).sum() > 100  # something was drawn on the white background


@pytest.mark.parametrize("size", ["64x", "640*480", "axb", "4x4", "100000x10"])
def test_bad_size_is_a_clean_error(run_cli, tmp_path, size):
    code, out, err = run_cli("render", "--size", size, "-o", str(tmp_path / "x.png"))
    assert code == 2
    assert "size" in err and "hint" in err
    assert "Traceback" not in err
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(("args", "message"), [
    (("--set", "genou=1"), "unknown joint 'genou'"),
    (("--set", "epaule=abc"), "not a number"),
    (("--background", "plaid"), "not a colour"),
    (("--fps", "0"), "--fps 0 is out of range"),
    (("--duration", "-1", "--gif", "x.gif"), "--duration -1"),
    (("--distance", "-2"), "distance"),
    (("--elevation", "120"), "elevation 120 is out of range"),
    (("--motion", "coude=import os"), "coude"),
])
def test_bad_values_are_clean_errors(run_cli, tmp_path, monkeypatch, args, message):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli("render", *SMALL, *args)
    assert code == 2
    assert message in err
    assert "Traceback" not in err
    assert os.listdir(tmp_path) == []


def test_out_of_limit_pose_is_drawn_with_a_warning(run_cli, tmp_path):
    code, _, err = run_cli("render", "--set", "coude=2.5", "-o", str(tmp_path / "p.png"), *SMALL)
    assert code == 0
    assert "coude=2.5 is above its upper limit 2 by 0.5 (drawn anyway)" in err


def test_motion_alone_makes_a_gif(run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli("render", "--motion", "coude=1.5*sin(t)", "--duration", "0.5", *SMALL)
    assert code == 0, err
    assert os.listdir(tmp_path) == ["bras.gif"]
    assert len(gif_info(tmp_path / "bras.gif")[1]) == 10


def test_motion_past_the_limits_warns(run_cli, tmp_path):
    code, _, err = run_cli("render", "--motion", "coude=2.5*sin(t)", "--duration", "2", "--fps", "5",
                           "--gif", str(tmp_path / "a.gif"), *SMALL)
    assert code == 0
    assert "coude" in err and "limit" in err


def test_command_module_imports_no_heavy_library():
    code = ("import sys, bras_kit.cli.render; "
            "print(sorted(m for m in ('pyrender', 'trimesh', 'PIL', 'imageio', 'OpenGL', 'scipy') if m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"


def test_antialias_flag_smooths_animation_frames(run_cli, tmp_path):
    from PIL import Image

    counts = {}
    for flag in ("--antialias", "--no-antialias"):
        folder = tmp_path / flag.strip("-")
        code, _, err = run_cli("render", *SMALL, "--duration", "0.1", "--fps", "10", "--no-grid",
                               "--frames-dir", str(folder), flag)
        assert code == 0, err
        image = np.asarray(Image.open(folder / "frame_0000.png"))
        counts[flag] = len(np.unique(image.reshape(-1, 3), axis=0))
    assert counts["--antialias"] > 2 * counts["--no-antialias"]


def test_unwritable_output_is_a_clean_error(run_cli, tmp_path):
    (tmp_path / "blocker").write_text("a file, not a folder")
    for option in ("-o", "--gif"):
        suffix = ".png" if option == "-o" else ".gif"
        code, _, err = run_cli("render", *SMALL, "--duration", "0.2", option, str(tmp_path / "blocker" / f"x{suffix}"))
        assert code == 2
        assert "cannot write" in err and "Traceback" not in err


def test_picture_name_must_say_its_format(run_cli, tmp_path):
    code, _, err = run_cli("render", *SMALL, "-o", str(tmp_path / "pose.pdf"))
    assert code == 2
    assert "cannot tell the picture format" in err and ".png" in err
