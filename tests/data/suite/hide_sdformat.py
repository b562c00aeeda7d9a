"""A pytest plugin (``-p hide_sdformat``) that makes this machine look as if libsdformat12-12 were
not installed: sdformat_oracle.library(), where the tests find it, answers None."""

import sdformat_oracle


def pytest_configure(config):  # noqa: ARG001 - pytest's hook signature
    sdformat_oracle.library = lambda: None
