# Hypothesis settings for the examples: reproducible runs (the README shows their output), no example
# database written into the source tree, no deadline (the exact references are slow on purpose).
import os

from hypothesis import settings

settings.register_profile("raykernel-examples", derandomize=True, database=None, deadline=None, max_examples=100)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "raykernel-examples"))
