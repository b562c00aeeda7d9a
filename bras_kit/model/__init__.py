"""The robot as data: the URDF reader, XML safety, expressions, xacro and the tutorial arm's
authoring."""
