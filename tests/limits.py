"""The test suite's time limits: only where a hang is the defect, generous, and named here.

A test never asserts how fast something ran (a busy machine is slow, and slow is not wrong:
speed is measured in ``benchmarks/``). A limit stays only where a child process, a browser page
or a server could wait forever, so that a hang fails one test instead of stopping the run. Each
limit is far beyond what a machine running two other CPU-bound jobs beside the suite needs
(``benchmarks/busy_test.sh``).
"""

#: s: a child process (the CLI, a Python snippet, pip, a notebook's cell) that has not ended in a
#: quarter of an hour hangs.
HANG_S = 900

#: ms: the same for a wait in the headless browser (Playwright counts in milliseconds).
HANG_MS = 1000 * HANG_S

#: s: a build that runs every example and writes the whole site (the docs) or installs a wheel
#: into a fresh virtualenv: an hour (the docs took 53 minutes at load 8-12 on two cores).
BUILD_S = 3600
