"""Frame sequences: GIF (frames, delays, palette, changed rectangles), MP4, numbered PNGs, progress."""

from __future__ import annotations

import io

import numpy as np
import pytest

from bras_kit.core.errors import ParameterError
from bras_kit.render import Progress, render_motion, save_frames, save_gif, save_mp4
from bras_kit.render.sequence import GifWriter, frame_name, gif_delay, palette_samples

SIZE = (160, 120)


@pytest.fixture(scope="module")
def states(tutorial_robot):
    from bras_kit.motion import sample, tutorial_motion

    return sample(tutorial_motion(tutorial_robot), 1.9, 10.0)  # 20 poses, 0 .. 1.9 s


@pytest.fixture(scope="module")
def frames(tutorial_robot, states):
    return list(render_motion(tutorial_robot, states, size=SIZE, view="iso"))


def read_gif(data: bytes):
    from PIL import Image

    image = Image.open(io.BytesIO(data))
    out, delays = [], []
    for index in range(image.n_frames):
        image.seek(index)
        delays.append(image.info["duration"])
        out.append(np.asarray(image.convert("RGB")))
    return out, delays


def test_motion_frames_are_drawn_lazily_and_counted(tutorial_robot, states, frames):
    sequence = render_motion(tutorial_robot, states, size=SIZE)
    assert len(sequence) == 20
    assert len(frames) == 20
    assert all(frame.shape == (120, 160, 3) and frame.dtype == np.uint8 for frame in frames)
    # the motion is visible: the arm at t = 0 and t = 1 s is not in the same place
    assert (np.abs(frames[0].astype(int) - frames[10].astype(int)).sum(axis=2) > 30).sum() > 200
    assert np.array_equal(sequence[10], frames[10])  # drawing one frame gives the same picture


def test_gif_has_every_frame_with_the_delay_of_its_fps(frames):
    buffer = io.BytesIO()
    assert save_gif(frames, buffer, fps=20) == 20
    decoded, delays = read_gif(buffer.getvalue())
    assert len(decoded) == 20
    assert delays == [50] * 20  # 1000 / 20 ms


def test_gif_frames_decode_to_the_rendered_frames(frames):
    # each frame stores only the rectangle that changed: decoding must rebuild whole pictures
    decoded, _ = read_gif(_gif(frames, fps=10))
    for original, back in zip(frames, decoded):
        difference = np.abs(original.astype(int) - back.astype(int))
        assert difference.mean() < 2.0
        assert np.percentile(difference.max(axis=2), 99) <= 24
    assert not np.array_equal(decoded[0], decoded[10])


def test_still_frames_are_kept_with_their_delay(frames):
    decoded, delays = read_gif(_gif([frames[0], frames[0], frames[5]], fps=10))
    assert len(decoded) == 3 and delays == [100, 100, 100]
    assert np.array_equal(decoded[0], decoded[1])


def _gif(frames, fps):
    buffer = io.BytesIO()
    save_gif(frames, buffer, fps=fps)
    return buffer.getvalue()


@pytest.mark.parametrize(("fps", "delay"), [(20, 5), (10, 10), (25, 4), (12, 8), (100, 2)])
def test_gif_delay_in_hundredths(fps, delay):
    assert gif_delay(fps) == delay


def test_gif_palette_comes_from_frames_spread_over_the_motion(tutorial_robot, states):
    sequence = render_motion(tutorial_robot, states, size=SIZE)
    samples, stream = palette_samples(sequence, 4)
    assert len(samples) == 4
    assert np.array_equal(samples[-1], sequence[19])  # the last pose is among them
    assert sum(1 for _ in stream) == 20
    plain = iter([np.zeros((8, 8, 3), np.uint8)] * 6)
    head, rest = palette_samples(plain, 4)
    assert len(head) == 4 and sum(1 for _ in rest) == 6  # borrowed frames are put back


def test_gif_refuses_frames_of_another_size(frames):
    writer = GifWriter(io.BytesIO(), 10, [frames[0]])
    writer.write(frames[0])
    with pytest.raises(ParameterError, match="same size"):
        writer.write(np.zeros((10, 10, 3), np.uint8))


def test_no_frames_is_an_error():
    with pytest.raises(ParameterError, match="no frames"):
        save_gif([], io.BytesIO(), fps=10)
    with pytest.raises(ParameterError, match="fps"):
        save_gif([np.zeros((8, 8, 3), np.uint8)], io.BytesIO(), fps=0)


def read_mp4(path) -> list[np.ndarray]:
    import imageio

    with imageio.get_reader(path, format="FFMPEG") as reader:
        return [np.asarray(frame) for frame in reader]


def test_mp4_reads_back_with_every_frame(frames, tmp_path):
    path = tmp_path / "anim.mp4"
    assert save_mp4(frames, path, fps=10) == 20
    video = read_mp4(path)
    assert len(video) == 20
    assert video[0].shape == (120, 160, 3)
    assert np.abs(video[10].astype(int) - frames[10].astype(int)).mean() < 6  # lossy, but the same picture


def test_mp4_pads_odd_sizes_to_even(tutorial_robot, states, tmp_path):
    odd = list(render_motion(tutorial_robot, states.positions[:3], size=(81, 61)))
    path = tmp_path / "odd.mp4"
    save_mp4(odd, path, fps=10)
    video = read_mp4(path)
    assert len(video) == 3 and video[0].shape == (62, 82, 3)  # yuv420p needs even sides


def test_frames_dir_holds_numbered_pngs(frames, tmp_path):
    from PIL import Image

    folder = tmp_path / "frames"
    assert save_frames(frames[:12], folder) == 12
    names = sorted(p.name for p in folder.iterdir())
    assert names == [f"frame_{i:04d}.png" for i in range(12)]
    assert np.array_equal(np.asarray(Image.open(folder / "frame_0007.png")), frames[7])


def test_frame_names_grow_past_four_digits():
    assert frame_name(7, 120) == "frame_0007.png"
    assert frame_name(12345, 20000) == "frame_12345.png"


def test_progress_bar_draws_on_a_terminal_only():
    terminal, piped = io.StringIO(), io.StringIO()
    bar = Progress(3, "rendering", stream=terminal, enabled=True)
    quiet = Progress(3, "rendering", stream=piped)  # StringIO is not a terminal
    for _ in range(3):
        bar.update()
        quiet.update()
    bar.close()
    quiet.close()
    assert "3/3 frames" in terminal.getvalue() and terminal.getvalue().endswith("\n")
    assert piped.getvalue() == ""


def test_joint_states_in_another_column_order_are_matched_by_name(tutorial_robot):
    from bras_kit.motion import JointStates
    from bras_kit.render import Renderer

    swapped = JointStates(np.array([0.0]), ["coude", "epaule"], np.array([[1.2, 0.8]]), np.zeros((1, 2)))
    with Renderer(tutorial_robot, size=SIZE) as renderer:
        by_name = next(renderer.frames(swapped))
        direct = renderer.render({"epaule": 0.8, "coude": 1.2})
    assert np.array_equal(by_name, direct)
    bad = JointStates(np.array([0.0]), ["genou"], np.array([[1.0]]), np.zeros((1, 1)))
    with pytest.raises(ParameterError, match="genou"):
        render_motion(tutorial_robot, bad)


def _colour_count(image: np.ndarray) -> int:
    return len(np.unique(image.reshape(-1, 3), axis=0))


def test_sequences_skip_antialiasing_unless_asked(tutorial_robot, states):
    from bras_kit.render import render_pose

    plain = render_motion(tutorial_robot, states, size=SIZE, grid=False)[5]
    smooth = render_motion(tutorial_robot, states, size=SIZE, grid=False, antialias=True)[5]
    picture = render_pose(tutorial_robot, states.positions[5], size=SIZE, grid=False)
    # blended edge pixels add colours: flat faces alone give a handful
    assert _colour_count(plain) < 30
    assert _colour_count(smooth) > 2 * _colour_count(plain)
    assert _colour_count(picture) > 2 * _colour_count(plain)  # single pictures are smooth by default
