"""Imported first, gpudelaunay sets OpenMP's short spin before libgomp loads, unless the
user chose a waiting of their own (README, Backends). argv[1]: the GOMP_SPINCOUNT expected
after the import ('' for none)."""
import os
import sys


def gomp_loaded():
    with open('/proc/self/maps') as maps:
        return any('libgomp' in line for line in maps)


if gomp_loaded():
    sys.exit('libgomp is loaded before the import: the test proves nothing')
import gpudelaunay  # noqa: E402,F401

expected = sys.argv[1] if len(sys.argv) > 1 else ''
got = os.environ.get('GOMP_SPINCOUNT', '')
if got != expected:
    sys.exit(f'GOMP_SPINCOUNT is {got!r} after the import, expected {expected!r}')
if not gomp_loaded():
    sys.exit('libgomp is not loaded after the import: the test proves nothing')
print('ok: GOMP_SPINCOUNT', repr(got))
