# pytest configuration for raykernel's Python tests (ctest label `python`; run them by hand with
# PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests).
#
# Hypothesis: no example database in the source tree, no deadline (exact references are slow on purpose),
# and the seed printed on failure (print_blob) so a CI failure can be reproduced with @reproduce_failure.
# RAYKERNEL_HYPOTHESIS_EXAMPLES raises the number of examples per property for longer local runs.
import os

from hypothesis import HealthCheck, settings

settings.register_profile(
    "raykernel",
    database=None,
    deadline=None,
    print_blob=True,
    max_examples=int(os.environ.get("RAYKERNEL_HYPOTHESIS_EXAMPLES", "200")),
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("raykernel")
