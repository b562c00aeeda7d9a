"""The learner's live ROS 2 graph: ``bras-kit doctor --ros`` and ``bras-kit view --ros``.

The real rclpy is met in one place, :mod:`._probe`, a script run by an interpreter that imports
it (:mod:`.interpreter` finds one); bras-kit reads what it prints (:mod:`.snapshot`), judges it
with the live rules of the registry (:mod:`bras_kit.validate.live`, BK8xx) and the URDF rules
on the description received (:mod:`.doctor`). Nothing here is imported on the start-up path.
"""
