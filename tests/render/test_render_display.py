"""Inline display in Jupyter: pictures, animations and videos as IPython display objects."""

from __future__ import annotations

import numpy as np

from bras_kit.render import render_motion, render_pose, save_mp4, show_gif, show_image, show_video


def test_show_image_embeds_a_png_of_the_picture(tutorial_robot):
    import io

    from PIL import Image

    picture = render_pose(tutorial_robot, {"epaule": 0.4}, size=(80, 60))
    shown = show_image(picture)
    assert shown.format == "png"
    assert shown.data[:8] == b"\x89PNG\r\n\x1a\n"
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(shown.data))), picture)


def test_show_gif_encodes_frames_in_memory(tutorial_robot):
    import io

    from PIL import Image

    frames = render_motion(tutorial_robot, np.array([[0.0, 0.0], [0.5, 0.5], [1.0, 1.0]]), size=(80, 60))
    shown = show_gif(frames, fps=10)
    assert shown.data[:6] == b"GIF89a"
    gif = Image.open(io.BytesIO(shown.data))
    assert gif.n_frames == 3 and gif.info["duration"] == 100


def test_show_gif_and_video_read_files(tutorial_robot, tmp_path):
    frames = list(render_motion(tutorial_robot, np.array([[0.0, 0.0], [0.5, 0.5]]), size=(80, 60)))
    path = tmp_path / "a.mp4"
    save_mp4(frames, path, fps=10)
    video = show_video(path)
    assert "video/mp4" in video._repr_html_() and "base64" in video._repr_html_()
    gif_path = tmp_path / "a.gif"
    gif_path.write_bytes(show_gif(frames, fps=10).data)
    assert show_gif(gif_path).data == gif_path.read_bytes()
