"""What a host program needs: the GIL released during long work, Ctrl-C honoured (and no file
left by an interrupted write), the installed wheel used, and help() that teaches."""

import os
import re
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import bumpmap


def test_the_installed_package_is_imported():
    # The tests run against the wheel installed into a virtual environment, not the source tree.
    here = Path(bumpmap.__file__).resolve()
    assert "site-packages" in here.parts, here
    native = Path(bumpmap._bumpmap.__file__).name
    assert ".abi3." in native, f"{native}: one wheel for CPython 3.9 and later (the stable ABI)"


def test_long_work_releases_the_gil():
    # One call of a few hundred milliseconds (the reference at 256², 64 samples per pixel) on
    # another thread. Holding the GIL, it would let this thread run at most once before and once
    # after it; released, this thread keeps ticking all through it.
    done = threading.Event()
    ticks = 0

    def work():
        bumpmap.render(technique="reference", size=256, spp=64)
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    thread.join()
    assert ticks > 10, f"the main thread ran {ticks} times during the work"


def run_and_interrupt(script: str, tmp_path: Path, after: float):
    """Runs `script`, sends SIGINT after `after` seconds, returns (stdout, stderr, seconds)."""
    # Python's own Ctrl-C handler, whatever the runner left: a shell's background job (`cmd &`)
    # starts with SIGINT ignored, which Python then keeps.
    script = "import signal; signal.signal(signal.SIGINT, signal.default_int_handler)\n" + textwrap.dedent(script)
    proc = subprocess.Popen([sys.executable, "-c", script], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # Wait for the script to say it started the work.
    assert proc.stdout.readline().strip() == "started"
    time.sleep(after)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    return out, err, time.monotonic() - sent


def test_ctrl_c_interrupts_a_long_render(tmp_path):
    # The reference at 512 samples per pixel on 512x512 takes minutes on two cores; Ctrl-C
    # ends the call with KeyboardInterrupt long before.
    out, err, seconds = run_and_interrupt(
        """
        import bumpmap, time
        print("started", flush=True)
        t = time.monotonic()
        try:
            bumpmap.render(technique="reference", size=512, spp=512)
            print("finished")
        except KeyboardInterrupt:
            print("interrupted after", time.monotonic() - t)
        """,
        tmp_path,
        after=1.0,
    )
    assert "interrupted after" in out, err
    assert seconds < 30


def test_an_interrupted_write_leaves_no_file(tmp_path):
    out, err, _ = run_and_interrupt(
        """
        import bumpmap, os, time
        chain = bumpmap.mip_chain(bumpmap.read_height_field("noise:3@4096"))
        print("started", flush=True)
        try:
            # BC7 of a 4096² chain takes seconds (5 MPix/s on two cores).
            bumpmap.write_texture("big.dds", chain, format="bc7")
            print("finished")
        except KeyboardInterrupt:
            # The work goes on in its thread to its end; wait for it, then look.
            time.sleep(10)
            print("left:", sorted(os.listdir(".")))
        """,
        tmp_path,
        after=0.5,
    )
    assert "left: []" in out, out + err


def test_help_lists_the_options_with_the_cli_defaults():
    doc = bumpmap.normal_map.__doc__
    assert "\n    scale = 4\n" in doc and "kernel = 'forward'" in doc
    # Each value with its meaning, as --help lists them; a flag's true and false are not listed.
    assert "One of:\n          - forward: F(u+1) − F(u)" in doc and "\n          - central: " in doc
    assert "One of: true, false" not in bumpmap.height_from_normals.__doc__
    render_doc = bumpmap.render.__doc__
    for option in ["technique = 'kilgard'", "backend = 'cpu'", "no_self_shadow: bool = False", "light = None",
                   "fov = 45", "torus_radii = (2.0, 0.7)"]:
        assert option in render_doc, option
    # The help texts speak of keywords, not of flags, but for a quoted command line, which a
    # user types as it stands (`normalmap --height-out`).
    outside_commands = re.sub(r"`[a-z][^`]*`", "", render_doc)
    assert "--" not in outside_commands, [line for line in outside_commands.splitlines() if "--" in line]
    assert "`normalmap --height-out` writes" in render_doc
    assert "normal_map's green" in render_doc
