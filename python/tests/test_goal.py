"""chore.Goal: a BDDL file's goal as `chore activity check` reads it, scored on given atoms."""

import pathlib

import pytest

import chore

ACTIVITIES = pathlib.Path(__file__).resolve().parents[2] / "tasks" / "activities"


def test_collect_trash_goal_is_its_forall_and_scores_on_atoms():
    goal = chore.Goal(str(ACTIVITIES / "collect_trash.bddl"))
    assert goal.domain == "igibson"
    assert ("ashcan.n.01_1", "ashcan.n.01") in goal.objects
    # Two conditions, a forall over the bottles and one over the cups: one option of four literals.
    assert goal.conditions == 2
    assert goal.options == [[0, 1, 2, 3]]
    assert goal.literals == [("inside", "bottle.n.01_1", "ashcan.n.01_1"), ("inside", "bottle.n.01_2", "ashcan.n.01_1"),
                             ("inside", "cup.n.01_1", "ashcan.n.01_1"), ("inside", "cup.n.01_2", "ashcan.n.01_1")]
    assert goal.score([]) == {"success": False, "q": 0.0, "satisfied": 0, "total": 4,
                              "condition_holds": [False, False], "best_option": 0}
    bottles = goal.score(goal.literals[:2])
    assert (bottles["success"], bottles["q"], bottles["condition_holds"]) == (False, 0.5, [True, False])
    done = goal.score(set(goal.literals) | {("ontop", "ashcan.n.01_1", "floor.n.01_1")})  # atoms off the goal: no matter
    assert (done["success"], done["q"], done["satisfied"]) == (True, 1.0, 4)


def test_bad_files_and_atoms_are_chore_errors_naming_them(tmp_path):
    with pytest.raises(chore.Error, match="no_such.bddl"):
        chore.Goal(str(tmp_path / "no_such.bddl"))
    bad = tmp_path / "bad.bddl"
    bad.write_text((ACTIVITIES / "collect_trash.bddl").read_text().replace("(inside ?", "(insid ?"))
    with pytest.raises(chore.Error, match=r"bad.bddl:\d+:\d+: .*insid"):
        chore.Goal(str(bad))
    goal = chore.Goal(str(ACTIVITIES / "collect_trash.bddl"))
    with pytest.raises(chore.Error, match=r"true_atoms\[1\]: expected a tuple"):
        goal.score([("open", "ashcan.n.01_1"), "open"])
    with pytest.raises(chore.Error, match=r"true_atoms\[0\]: expected a predicate and at least one object"):
        goal.score([("open",)])
    with pytest.raises(chore.Error, match=r"true_atoms\[0\]\[1\]: expected a str"):
        goal.score([("open", 3)])
