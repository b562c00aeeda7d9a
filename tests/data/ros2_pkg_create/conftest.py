# The packages here are what `ros2 pkg create` writes, tests included: data for bras-kit's tests,
# never tests of bras-kit's own suite.
collect_ignore_glob = ["*"]
