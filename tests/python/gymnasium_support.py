"""Gymnasium for the tests of campo.gym and what uses it (test_gym, test_learn_example, ...).

Installed, else from CAMPO_GYMNASIUM_PATH (the unmodified copy vendored beside the repository, which
tests/CMakeLists.txt finds). Without either, the tests needing it are skipped with the reason, unless
CAMPO_REQUIRE_GYMNASIUM=1 (as .ci/run sets), where they fail with it.
"""

import os
import sys
import unittest

if os.environ.get("CAMPO_GYMNASIUM_PATH"):
    sys.path.append(os.environ["CAMPO_GYMNASIUM_PATH"])
try:
    import gymnasium  # noqa: F401 (imported for the tests that use it)

    GYMNASIUM_ERROR = None
except ImportError as error:
    GYMNASIUM_ERROR = (f"Gymnasium cannot be imported ({error}); pip install 'gymnasium>=1.0' or set "
                       "CAMPO_GYMNASIUM_PATH")

REQUIRED = os.environ.get("CAMPO_REQUIRE_GYMNASIUM") == "1"


def needs_gymnasium(cls):
    """A TestCase class that needs Gymnasium: skipped without it, failing without it where it is required."""
    if GYMNASIUM_ERROR is None:
        return cls
    if not REQUIRED:
        return unittest.skip(GYMNASIUM_ERROR)(cls)

    def set_up(self):
        self.fail(GYMNASIUM_ERROR + " (CAMPO_REQUIRE_GYMNASIUM=1)")

    cls.setUp = set_up
    cls.setUpClass = classmethod(lambda c: None)
    return cls
