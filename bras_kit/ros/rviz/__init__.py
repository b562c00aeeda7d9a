"""What robot_state_publisher and RViz do with a launch: ``frames`` (the transforms, and which links
RViz can place) and ``config`` (what a ``.rviz`` sets RViz to show, and what it then shows)."""
