"""The automatic polycube stops when its label repair is not converging (issue 19: "the polycube
path stops early when its repair is not converging, instead of running for minutes").

The part is one of our own corpus's (bench/make_corpus.py, box_thin family, 7th draw of the default
seed: a thin-walled open box with rounded corners), made here by FreeCAD. On its tessellation
segmented with lambda 0.1, the polycube map makes the bottom's -Z chart and a +Z chart overlap; the
round relabels a small +Z chart beside them, the label repair takes most of that back, and the next
round ends in the very same problem: before the check, ten rounds did so (about 5 s, four times
over the edge weights under `auto`), never reaching a labelling seen before, so the cycle check did
not stop them. Over the corpus (217 parts and the 9 CAD parts, auto, session 31's logs) no run of
rounds ending in the same problem more than twice in a row ever ended in a polycube. The oracle is
the run itself: with the default (3) the message says the repair is not converging after 3 rounds;
allowed 6, the same labelling runs 6 rounds and says so (so the stop is this check's, not another
limit's)."""

import re

import pytest

import hexdom_test_support as support


@pytest.fixture(scope="module")
def labels(freecad, core, tmp_path_factory):
    return support.segmented_corpus_part(core, tmp_path_factory.mktemp("box_thin"), "box_thin", 6)


def test_rounds_ending_in_the_same_problem_stop_the_repair(core, labels):
    s, size = labels
    with pytest.raises(core.GeometryError) as e:
        core.autopolycube(s, size=size, level=1)
    message = str(e.value)
    print(message)
    assert re.search(r"overlap in the polycube.*the same problem after 3 rounds of relabelling: the label repair is not "
                     r"converging", message, re.S), message
    with pytest.raises(core.GeometryError) as longer:
        core.autopolycube(s, size=size, level=1, max_same_problem=6)
    print(longer.value)
    assert "the same problem after 6 rounds" in str(longer.value)
    with pytest.raises(core.GeometryError):
        core.autopolycube(s, size=size, level=1, max_same_problem=0)
