# Benchmarks of sim.
