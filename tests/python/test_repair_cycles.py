"""The automatic polycube stops when its label repair cycles (issue 19: "the polycube path stops
early when its repair is not converging, instead of running for minutes").

The part is one of our own corpus's (bench/make_corpus.py, counterbore family, 6th draw of the
default seed: a plate with counterbores, countersinks and spot faces), made here by FreeCAD. On its
tessellation segmented with lambda 0.1, the polycube map makes two charts overlap; relabelling the
smaller one and the repair that follows give, after a few rounds, a labelling the repair had
already mapped, and from there the same rounds again. Before the check, autopolycube went on for
its 20 rounds (about 25 s here, over its four edge weights and five tessellations several minutes
under `--method polycube`); now it stops the first time a labelling comes back and says so. The
oracle is the run itself: the message names the cycle and the rounds, which are fewer than the
rounds allowed (max_attempts), and the same run with max_attempts below that count ends on the
round limit instead (so the stop is the cycle's, not a limit's)."""

import re

import pytest

import hexdom_test_support as support


@pytest.fixture(scope="module")
def labels(freecad, core, tmp_path_factory):
    return support.segmented_corpus_part(core, tmp_path_factory.mktemp("counterbore"), "counterbore", 5)


def test_a_label_repair_that_comes_back_to_a_labelling_stops(core, labels):
    s, size = labels
    with pytest.raises(core.GeometryError) as e:
        core.autopolycube(s, size=size, level=1)
    message = str(e.value)
    print(message)
    m = re.search(r"came back to a labelling it had mapped, after (\d+) rounds: it cycles", message)
    assert m, message
    rounds = int(m.group(1))
    assert 2 <= rounds < 20  # 20: AutoPolycubeOptions::max_attempts
    with pytest.raises(core.GeometryError) as limited:
        core.autopolycube(s, size=size, level=1, max_attempts=rounds - 1)
    assert "it cycles" not in str(limited.value)
