"""compare against `bumpmap compare`: the same results, and the same report folder."""

import json

import pytest

import bumpmap

OPTIONS = {"size": 32, "spp": 4, "techniques": ["kilgard", "no-bump", "emboss"]}
FLAGS = ["--size", "32", "--spp", "4", "--techniques", "kilgard,no-bump,emboss"]


# FLIP's means come from NVIDIA's C++ library (nv-flip), which the wheel's modules are built
# with zig's clang (for manylinux2014) and the command line with the system's g++: the same
# heat maps byte for byte, but the means summed over them can differ in the sixth decimal
# (seen: 2e-6). Every other number must be equal.
FLIP_TOLERANCE = 1e-5


def without_times(value, flips=None, path=""):
    """The results but their wall-clock times, which differ from run to run, and (put in
    `flips` by path, when given) their FLIP means."""
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            if k in ("millis", "total_millis"):
                continue
            if flips is not None and "flip" in k and isinstance(v, (int, float)):
                flips[f"{path}.{k}"] = v
            elif flips is not None and "flip" in k and isinstance(v, dict):
                flips.update({f"{path}.{k}.{n}": x for n, x in v.items()})
            else:
                out[k] = without_times(v, flips, f"{path}.{k}")
        return out
    if isinstance(value, list):
        return [without_times(v, flips, f"{path}[{i}]") for i, v in enumerate(value)]
    return value


@pytest.fixture(scope="module")
def both(tmp_path_factory, cli):
    folder = tmp_path_factory.mktemp("compare")
    cli("compare", "-o", folder / "cli", *FLAGS)
    ours = bumpmap.compare(folder / "ours", **OPTIONS)
    return folder, ours


def test_results_equal_the_cli(both):
    folder, ours = both
    theirs = json.loads((folder / "cli" / "results.json").read_text())
    our_flips, their_flips = {}, {}
    assert without_times(ours, our_flips) == without_times(theirs, their_flips)
    assert our_flips.keys() == their_flips.keys() and len(our_flips) > 20
    far = {k: (v, their_flips[k]) for k, v in our_flips.items() if abs(v - their_flips[k]) > FLIP_TOLERANCE}
    assert not far, far
    assert set(ours["techniques"]) == {"kilgard", "no-bump", "emboss"}
    assert all(15 < t["psnr"] < 60 for t in ours["techniques"].values())


def test_the_report_folder_is_the_cli_s(both):
    folder, _ = both
    names = lambda d: sorted(p.name for p in d.iterdir())  # noqa: E731
    assert names(folder / "ours") == names(folder / "cli")
    for name in ["kilgard.png", "reference.png", "no-bump.flip.png"]:
        assert (folder / "ours" / name).read_bytes() == (folder / "cli" / name).read_bytes()
    assert "kilgard" in (folder / "ours" / "report.html").read_text()


def test_without_output_nothing_is_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    # A technique that cannot be measured is skipped with its reason; a name that is none is
    # refused before the work.
    results = bumpmap.compare(size=16, spp=1, techniques=["single-pass", "reference"])
    assert "single-pass" in results["techniques"]
    assert "reference" in results["skipped"]
    with pytest.raises(ValueError, match="'nonsense' is not a technique"):
        bumpmap.compare(size=16, spp=1, techniques=["single-pass", "nonsense"])
    assert list(tmp_path.iterdir()) == []


def test_an_output_that_is_a_file_is_refused_before_the_work(tmp_path):
    path = tmp_path / "report"
    path.write_text("mine")
    with pytest.raises(OSError, match="is a file"):
        bumpmap.compare(path, size=16, spp=1)
    assert path.read_text() == "mine"
    with pytest.raises(ValueError, match=r"unknown scene 'mesh:x.obj'"):
        bumpmap.compare(scene="mesh:x.obj")
