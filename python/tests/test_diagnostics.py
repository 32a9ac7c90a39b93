"""What the work says besides its result reaches Python as Python expects: warnings through
`warnings` (category `bumpmap.BumpmapWarning`, so a filter can silence them or make them errors),
notes through the `bumpmap` logger, progress through a `progress=` function called on the
caller's thread — and nothing of it on stderr."""

import logging
import warnings

import numpy as np
import pytest

import bumpmap


def out_of_range():
    return np.linspace(-0.5, 1.5, 64, dtype=np.float32).reshape(8, 8)


def test_a_warning_is_a_python_warning_at_the_callers_line_and_not_on_stderr(capfd):
    with pytest.warns(bumpmap.BumpmapWarning, match=r"heights from -0\.5 to 1\.5 are clamped to \[0, 1\]") as caught:
        bumpmap.height_mips(out_of_range())
    assert len(caught) == 1 and caught[0].filename == __file__
    assert issubclass(bumpmap.BumpmapWarning, UserWarning)
    assert "clamped" not in capfd.readouterr().err


def test_a_warnings_filter_makes_it_an_error_or_silences_it():
    with warnings.catch_warnings():
        warnings.simplefilter("error", bumpmap.BumpmapWarning)
        with pytest.raises(bumpmap.BumpmapWarning, match="clamped"):
            bumpmap.height_mips(out_of_range())
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("ignore", bumpmap.BumpmapWarning)
        levels, _ = bumpmap.height_mips(out_of_range())
    assert caught == [] and levels[0].max() == 1.0


def test_notes_go_to_the_bumpmap_logger(caplog, capfd):
    # A technique compare cannot measure is skipped with a note: the reference itself.
    with caplog.at_level(logging.INFO, logger="bumpmap"):
        bumpmap.compare(size=24, spp=1, studies="none", techniques=["kilgard", "reference"])
    skipped = [r for r in caplog.records if r.name == "bumpmap" and "skipped reference" in r.getMessage()]
    assert len(skipped) == 1 and skipped[0].levelno == logging.INFO, [r.getMessage() for r in caplog.records]
    assert "skipped" not in capfd.readouterr().err


def test_progress_counts_the_references_tiles_then_ends_at_its_total():
    seen = []
    image = bumpmap.render(technique="reference", size=48, spp=1, progress=lambda done, total: seen.append((done, total)))
    assert image[..., :3].max() > 50
    totals = {t for _, t in seen}
    assert len(totals) == 1 and totals.pop() > 1, seen
    done = [d for d, _ in seen]
    assert done == sorted(done) and seen[-1][0] == seen[-1][1], seen


def test_progress_of_a_technique_is_one_step_and_of_compare_every_step():
    seen = []
    bumpmap.render(technique="kilgard", size=32, progress=lambda *a: seen.append(a))
    assert seen == [(1, 1)]
    seen.clear()
    bumpmap.compare(size=24, spp=1, studies="none", techniques=["kilgard", "single-pass"], progress=lambda *a: seen.append(a))
    assert seen[-1] == (12, 12) and len(seen) >= 2, seen  # 2 techniques + the references, convergence, 7 studies


def test_progress_of_the_horizon_map_counts_its_rows():
    seen = []
    heights = bumpmap.read_height_field("bricks@64")
    plain = bumpmap.horizon_maps(heights)
    told = bumpmap.horizon_maps(heights, progress=lambda *a: seen.append(a))
    # The calling thread reads the count as it goes (a quick map may be told only its end).
    assert {t for _, t in seen} == {64} and seen[-1] == (64, 64), seen
    done = [d for d, _ in seen]
    assert done == sorted(done), seen
    # Telling changes nothing made.
    assert all(np.array_equal(a, b) for a, b in zip(plain["horizons"], told["horizons"]))

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop(f"{done}/{total}")

    with pytest.raises(Stop):
        bumpmap.horizon_maps(heights, progress=stop)


def test_progress_of_a_render_that_makes_a_horizon_map_counts_its_rows():
    seen = []
    told = bumpmap.render(technique="horizon", height_field="bricks@128", size=32, progress=lambda *a: seen.append(a))
    # The horizon map's rows (the calling thread reads the count as it goes), ending at its total.
    assert {t for _, t in seen} == {128} and seen[-1] == (128, 128), seen
    assert np.array_equal(told, bumpmap.render(technique="horizon", height_field="bricks@128", size=32))

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop(f"{done}/{total}")

    with pytest.raises(Stop, match="/128"):
        bumpmap.render(technique="horizon", height_field="bricks@128", size=32, progress=stop)


def test_a_progress_function_that_raises_stops_the_call_with_its_exception():
    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop(f"{done}/{total}")

    with pytest.raises(Stop):
        bumpmap.render(technique="reference", size=64, spp=4, progress=stop)
    with pytest.raises(TypeError, match=r"progress: a function of \(done, total\) or None, not str"):
        bumpmap.render(progress="yes")
    assert bumpmap.render(size=16, progress=None).shape == (16, 16, 4)


def test_prepare_says_its_notes_as_render_does(caplog, capfd):
    """A scene prepared once says what setting it up noted, through the logger, as `render`
    says it each call; `Scene.notes` keeps the lines, in the same words."""
    with caplog.at_level(logging.INFO, logger="bumpmap"):
        scene = bumpmap.Renderer().prepare(technique="pom", depth=100, size=16)
    said = [r.getMessage() for r in caplog.records if r.name == "bumpmap" and "carve past" in r.getMessage()]
    assert len(said) == 1, [r.getMessage() for r in caplog.records]
    assert any("carve past" in n for n in scene.notes)
    # In Python's words, as the logger says them: keywords, not the command line's flags.
    assert said[0] in scene.notes
    assert not any("--" in n for n in scene.notes), scene.notes
    assert "carve past" not in capfd.readouterr().err
