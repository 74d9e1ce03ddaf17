# Benchmarks of global.
