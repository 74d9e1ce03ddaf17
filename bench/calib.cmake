# Benchmarks of calib.
