"""RViz as the learner's launch starts it, modelled from the sources of the tools themselves.

Two halves, one model read by the page, ``view --ros`` and ``doctor --ros``:

- :mod:`.frames`: what robot_state_publisher 3.3.3 does with each JointState it receives, what tf2
  keeps of the transforms it publishes, and which links RViz can then place in the Fixed Frame;
- :mod:`.config`: what RViz is set to show (a ``.rviz`` file or RViz's own default) and what it
  draws from the transforms the first half gives.
"""
