"""Two models meshed in two Python threads against one after the other: the
module releases the GIL while it loads, sizes and meshes, so on two cores
the threads should take clearly less wall time. Prints the ratio.

PYTHONPATH=build/python /usr/bin/python3 bench/python_threads.py [MODEL_A MODEL_B]
"""
import os
import sys
import threading
import time

import sizemesh

here = os.path.dirname(os.path.abspath(__file__))
models = sys.argv[1:3] or [os.path.join(here, "..", "tests", "data", f)
                           for f in ("onera_m6_wing.stp", "cylinder_head_fins.stp")]
# One thread per model inside the mesher too would hide the effect: one each.
options = dict(threads=1)

t0 = time.perf_counter()
for m in models:
    sizemesh.mesh(m, **options)
sequential = time.perf_counter() - t0

t0 = time.perf_counter()
threads = [threading.Thread(target=sizemesh.mesh, args=(m,), kwargs=options) for m in models]
for t in threads:
    t.start()
for t in threads:
    t.join()
parallel = time.perf_counter() - t0
print("one after the other %.2f s, two threads %.2f s: ratio %.2f" % (sequential, parallel, parallel / sequential))
