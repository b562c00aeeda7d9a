"""bras-kit: describe, check, move and show a robot arm with no ROS install.

The library API used by notebooks and the CLI. Every name is imported on first use, so
``import bras_kit`` (and ``bras-kit --help``) stays light.
"""

from __future__ import annotations

from .core.lazy import lazy_exports

__version__ = "0.1.0"

# name -> module providing it, imported on first access (keeps `import bras_kit` fast)
_LAZY = {
    "arm": "bras_kit.model.authoring",
    "arm_urdf": "bras_kit.model.authoring",
    "load": "bras_kit.model.authoring",
    "template_parameters": "bras_kit.model.authoring",
    "expand_xacro": "bras_kit.model.xacro",
    "fk": "bras_kit.kinematics.frames",
    "fk_batch": "bras_kit.kinematics.frames",
    "relative_transform": "bras_kit.kinematics.frames",
    "tf_tree": "bras_kit.kinematics.frames",
    "Robot": "bras_kit.model.robot",
    "Link": "bras_kit.model.robot",
    "Joint": "bras_kit.model.robot",
    "BrasKitError": "bras_kit.core.errors",
    "ModelError": "bras_kit.core.errors",
    "ParameterError": "bras_kit.core.errors",
    "XacroError": "bras_kit.core.errors",
    "XMLSafetyError": "bras_kit.core.errors",
    "XMLSyntaxError": "bras_kit.core.errors",
    "validate": "bras_kit.validate",
    "validate_path": "bras_kit.validate",
    "describe_transform": "bras_kit.kinematics.frames",
    "tool_tip": "bras_kit.kinematics.tip",
    "formula_motion": "bras_kit.motion",
    "waypoint_motion": "bras_kit.motion",
    "pose_motion": "bras_kit.motion",
    "motion_from_specs": "bras_kit.motion",
    "sample": "bras_kit.motion",
    "sample_loop": "bras_kit.motion",
    "check_limits": "bras_kit.motion",
    "JointStates": "bras_kit.motion",
    "Renderer": "bras_kit.render",
    "save_png": "bras_kit.render",
    "show_image": "bras_kit.render",
    "show_gif": "bras_kit.render",
    "frames_dot": "bras_kit.diagrams",
    "tree_text": "bras_kit.diagrams",
    "reach_motion": "bras_kit.ik",
    "workspace_figure": "bras_kit.ik",
    "scaffold_package": "bras_kit.scaffold.package",
    "Motion": "bras_kit.motion",
    "tutorial_motion": "bras_kit.motion",
    "render_pose": "bras_kit.render",
    "render_motion": "bras_kit.render",
    "save_gif": "bras_kit.render",
    "save_mp4": "bras_kit.render",
    "frame_diagram": "bras_kit.diagrams",
    "plot_motion": "bras_kit.diagrams",
    "solve_ik": "bras_kit.ik",
    "ik_2r": "bras_kit.ik",
    "jacobian": "bras_kit.ik",
    "simulate": "bras_kit.physics",
    "build_mjcf": "bras_kit.physics",
    "view": "bras_kit.view",
    "set_language": "bras_kit.core.i18n",
    "say": "bras_kit.core.i18n",
    "run_node": "bras_kit.run",
    "run_findings": "bras_kit.run",
}


__getattr__ = lazy_exports(__name__, _LAZY)


__all__ = ["__version__", *_LAZY]


def __dir__() -> list[str]:
    return __all__
