"""The MuJoCo peer of the render benchmarks, run by another Python (a virtualenv with ``mujoco``,
``numpy`` and ``pillow``: MuJoCo's renderer needs a newer PyOpenGL than the 3.1.0 bras-kit pins
for pyrender, so it cannot share bras-kit's environment).

    python _mujoco_peer.py MODEL.xml OUT.png|OUT.gif FRAMES FPS WIDTH HEIGHT [swing]

Loads the MJCF (built by ``bras-kit mjcf`` from the URDF: MuJoCo's own URDF import drops the
visuals), renders FRAMES pictures with ``mujoco.Renderer`` on EGL from a free camera looking at
the model's centre, moving the joints as the pybullet scripts do (the tutorial's two-joint sine;
with ``swing``, every joint about the middle of its limits), and writes one still (PNG) or a
GIF with Pillow. Standard library, numpy, Pillow and mujoco only: bras-kit is not
importable here.
"""

from __future__ import annotations

import math
import os
import sys

os.environ.setdefault("MUJOCO_GL", "egl")


def main() -> None:
    import mujoco
    import numpy as np
    from PIL import Image

    path, out = sys.argv[1], sys.argv[2]
    count, fps, width, height = int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6])
    model = mujoco.MjModel.from_xml_path(path)
    model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)
    model.vis.global_.offheight = max(model.vis.global_.offheight, height)
    data = mujoco.MjData(model)
    renderer = mujoco.Renderer(model, height, width)
    camera = mujoco.MjvCamera()
    mujoco.mjv_defaultFreeCamera(model, camera)
    camera.azimuth, camera.elevation = 235.0, -25.0  # about the pictures' iso view
    moving = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))  # the enum is no int
    hinges = [j for j in range(model.njnt) if int(model.jnt_type[j]) in moving]
    swing = sys.argv[7:8] == ["swing"]
    frames = []
    for k in range(count):
        t = k / fps
        for n, joint in enumerate(hinges if swing else hinges[:2]):
            if swing:
                low, high = model.jnt_range[joint] if model.jnt_limited[joint] else (-1.0, 1.0)
                value = (low + high) / 2 + (high - low) / 4 * math.sin(2 * math.pi * t / 6 + n)
            else:  # the tutorial's motion
                value = (0.8 * math.sin(t)) if n == 0 else (1.2 * math.sin(0.7 * t))
            data.qpos[model.jnt_qposadr[joint]] = value
        mujoco.mj_kinematics(model, data)
        renderer.update_scene(data, camera)
        frames.append(Image.fromarray(np.asarray(renderer.render())))
    if len(frames) == 1:
        frames[0].save(out)
    else:
        frames[0].save(out, save_all=True, append_images=frames[1:], duration=1000 // fps, loop=0)
    renderer.close()


if __name__ == "__main__":
    main()
