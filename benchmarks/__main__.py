"""``python -m benchmarks``: the benchmark's command line (:func:`benchmarks.run.main`)."""

import sys

from benchmarks.run import main

sys.exit(main())
