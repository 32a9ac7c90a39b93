"""Which build of the native module this process loads.

The published wheel carries it twice: ``_bumpmap``, built for any x86-64 processor, and
``_bumpmap_x86_64_v3``, built for x86-64-v3 (AVX2, FMA, BMI2, ...: Intel since 2013, AMD since
2015), where the CPU pipeline runs four to five times faster. The faster one is loaded where the
processor has what it needs (asked of the first, which runs anywhere); both give the same bytes.
A build from source (``pip install ./python``) holds one module, built for the machine that
built it, and that is the one loaded.

``BUMPMAP_CPU=x86-64`` in the environment loads the baseline module whatever the processor
(to compare the two); ``BUMPMAP_CPU=x86-64-v3`` insists on the faster one and fails to import
where it cannot run.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys
from pathlib import Path

from . import _bumpmap as _baseline

FAST_STEM = "_bumpmap_x86_64_v3"
CHOICES = ("auto", "x86-64", "x86-64-v3")


def load():
    """The native module for this processor, registered as ``bumpmap._bumpmap``."""
    asked = os.environ.get("BUMPMAP_CPU", "auto")
    if asked not in CHOICES:
        raise ImportError(f"BUMPMAP_CPU={asked!r}: expected one of {', '.join(CHOICES)}")
    built = _baseline.built_for()
    here = Path(__file__).parent
    fast = [here / (FAST_STEM + s) for s in importlib.machinery.EXTENSION_SUFFIXES if (here / (FAST_STEM + s)).is_file()]
    if asked == "auto":
        if built == "x86-64-v3" or not fast or not _baseline.runs_x86_64_v3():
            return _baseline
    elif asked == built:
        return _baseline
    elif asked == "x86-64":
        raise ImportError("BUMPMAP_CPU=x86-64: this installation holds only a build for x86-64-v3")
    elif not fast:
        raise ImportError("BUMPMAP_CPU=x86-64-v3: this installation holds no build for x86-64-v3")
    elif not _baseline.runs_x86_64_v3():
        raise ImportError("BUMPMAP_CPU=x86-64-v3: this processor lacks x86-64-v3 (AVX2, FMA, BMI2)")
    # Loaded under the baseline's name: the init function a module file must export is named
    # after the module (PyInit__bumpmap), and both files export it.
    spec = importlib.util.spec_from_file_location(_baseline.__name__, fast[0])
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    sys.modules[_baseline.__name__] = module
    return module
