# Tests python/errors.cpp: the gpm module's errors in Python's words (keywords
# for the library's command-line flags), gpm.InputTypeError for arguments of
# the wrong type, and numbers out of range (of any size) naming the keyword
# and the valid range.
import numpy as np
import pytest

import gpm

FLAG = "--"


@pytest.fixture(scope="module")
def readings():
    robot = gpm.load_robot()
    xs = np.linspace(150.0, 280.0, 5)
    return robot.ik(np.array([[x, y] for x in xs for y in np.linspace(190.0, 310.0, 5)]))


def test_the_exception_classes():
    assert issubclass(gpm.InputError, ValueError) and issubclass(gpm.InputError, gpm.Error) is False
    assert issubclass(gpm.InputTypeError, gpm.InputError) and issubclass(gpm.InputTypeError, TypeError)
    assert issubclass(gpm.Error, RuntimeError) and issubclass(gpm.SimError, gpm.Error)


@pytest.mark.parametrize("flags, python", [
    ("--fix: every parameter is fixed", "fix: every parameter is fixed"),
    ("fix 2 more (the default --fix xa1,ya1,xa2,ya2 removes it), or pass --allow-rank-deficient for a solution",
     'fix 2 more (the default fix=["xa1", "ya1", "xa2", "ya2"] removes it), or pass allow_rank_deficient=True '
     'for a solution'),
    ("--cost ml works with lm or de+lm only", 'cost="ml" works with lm or de+lm only'),
    ("--cost j3: la1 and dth1; or use --cost ml or j2", 'cost="j3": la1 and dth1; or use cost="ml" or j2'),
    ("check --model and the offsets", "check robot and the offsets"),
    ("--budget: LM needs at least one iteration", "budget: LM needs at least one iteration"),
    ("--fix[2]: unknown parameter", "fix[2]: unknown parameter"),
    ("use a robust loss (--loss cauchy)", "use a robust loss (gpm calibrate --loss cauchy)"),
    # A command quoted for the command line keeps its flags; the rest is translated.
    ("give at least 12 (gpm design --count 12); --sigma too", "give at least 12 (gpm design --count 12); sigma too"),
    ("take samples with `gpm run --hardware`", "take samples with `gpm run --hardware`"),
    ("--fixed-point and --modelling are other words", "--fixed-point and --modelling are other words"),
    ("/tmp/a--fix.yaml: cannot open file (--fix)", "/tmp/a--fix.yaml: cannot open file (fix)"),
    ("'--sigma' and [--seed]", "'sigma' and [seed]"),
])
def test_flags_become_keywords(flags, python):
    assert gpm._python_words(flags) == python


def test_a_rank_deficient_free_set_says_allow_rank_deficient_true(readings):
    with pytest.raises(gpm.InputError) as e:
        gpm.calibrate(readings, gpm.load_robot(), fix=["xa1", "ya1"])
    text = str(e.value)
    assert text.startswith("fix: the 13 free parameters")
    assert "pass allow_rank_deficient=True" in text and 'fix=["xa1", "ya1", "xa2", "ya2"]' in text
    assert FLAG not in text
    # ... and the advice works.
    with pytest.warns(RuntimeWarning):
        r = gpm.calibrate(readings, gpm.load_robot(), fix=["xa1", "ya1"], allow_rank_deficient=True)
    assert r.diagnostics["rank_deficient"]


@pytest.mark.parametrize("kwargs, start, valid", [
    (dict(budget=10**19), "budget: must be a whole number from 1 to 1e6 iterations, got '10000000000000000000'", ""),
    (dict(budget=-10**40), "budget: must be", "1 to 1e6 iterations"),
    (dict(budget=0, method="de"), "budget: must be a whole number from 1 to 1e10 evaluations", ""),
    (dict(budget=2.5), "budget: must be a whole number", "1 to 1e6"),
    (dict(seed=10**30), "seed: must be a whole number from 0 to 9007199254740992", ""),
    (dict(seed=2**53 + 1), "seed: must be a whole number from 0 to 9007199254740992", ""),
    (dict(seed=-1), "seed: must be", "from 0"),
    (dict(encoder_bits=10**25), "encoder_bits: must be a whole number from 0 to 40 bits", ""),
    (dict(sigma=10**400), "sigma: must be a number from 1e-12 to 1 rad", ""),
    (dict(sigma=0.0), "sigma: must be a number from 1e-12 to 1 rad", ""),
])
def test_numbers_out_of_range_raise_value_error_naming_the_keyword_and_the_range(readings, kwargs, start, valid):
    with pytest.raises(ValueError) as e:
        gpm.calibrate(readings, gpm.load_robot(), **kwargs)
    assert isinstance(e.value, gpm.InputError) and not isinstance(e.value, TypeError)
    assert str(e.value).startswith(start) and valid in str(e.value)


def test_numbers_in_range_of_any_integer_type_are_taken(readings):
    r = gpm.calibrate(readings, gpm.load_robot(), budget=np.int64(50), seed=np.uint8(3), encoder_bits=17)
    assert r.converged
    r = gpm.calibrate(readings, gpm.load_robot(), budget=1e2, sigma=np.float32(1e-4))
    assert r.converged


@pytest.mark.parametrize("call, start", [
    (lambda R: gpm.calibrate(R, gpm.load_robot(), budget="10"), "budget: expected a whole number from 1 to 1e6"),
    (lambda R: gpm.calibrate(R, gpm.load_robot(), budget=True), "budget: expected a whole number"),
    (lambda R: gpm.calibrate(R, gpm.load_robot(), seed=[1]), "seed: expected a whole number from 0"),
    (lambda R: gpm.calibrate(R, gpm.load_robot(), sigma="1e-4"), "sigma: expected a number from 1e-12 to 1 rad"),
    (lambda R: gpm.calibrate(R, gpm.load_robot(), encoder_bits=None, sigma=1j), "sigma: expected a number"),
    (lambda R: gpm.calibrate(R, "gpm2002.yaml"), "robot: expected a gpm.Robot (gpm.load_robot(path)"),
    (lambda R: gpm.calibrate(R, gpm.load_robot(), fix=3), 'fix: expected a list of parameter names (e.g. ["xa1"'),
    (lambda R: gpm.calibrate(R, gpm.load_robot(), fix=[1, 2]), "fix: expected parameter names (str), got int"),
    (lambda R: gpm.calibrate("abc", gpm.load_robot()), "readings: expected an array of numbers of shape (n, 3)"),
    (lambda R: gpm.calibrate(R, gpm.load_robot(), t="abc"), "t: expected an (n,) array of times"),
    (lambda R: gpm.design(count="50"), "count: expected a whole number from 1 to 10000 poses, got str"),
    (lambda R: gpm.design(grid_step=None), "grid_step: expected a number from 1 to 100 mm, got NoneType"),
    (lambda R: gpm.design(robot="nominal"), "robot: expected a gpm.Robot"),
    (lambda R: gpm.crb(gpm.load_robot(), readings=R, sigma="x"), "sigma: expected a number"),
    (lambda R: gpm.pose_bounds(None, [[216.5, 250.0]] * 12), "robot: expected a gpm.Robot, "),
    (lambda R: gpm.Robot(geometry=[("la1", 244.0)]), "geometry: expected a dict of parameters"),
    (lambda R: gpm.Robot(geometry={"la1": "244"}), "geometry: la1 must be a number in mm or rad, got str"),
    (lambda R: gpm.population_robot_scenario(gpm.scenarios_dir() + "/main.yaml", "7"), "seed: expected a whole"),
    (lambda R: gpm.load_robot(42), "path: expected a path (str or os.PathLike), got int"),
])
def test_wrong_types_raise_type_error_naming_the_keyword(readings, call, start):
    with pytest.raises(TypeError) as e:
        call(readings)
    assert isinstance(e.value, gpm.InputTypeError) and isinstance(e.value, ValueError)
    text = str(e.value)
    assert text.startswith(start.replace("gpm.Robot, ", "gpm.Robot")) and "\n" not in text, text


def test_population_robot_scenario_seed_of_any_size():
    with pytest.raises(gpm.InputError, match=r"^seed: must be a whole number from 0 to 9007199254740992, got "
                                             r"'10000000000000000000'$"):
        gpm.population_robot_scenario(gpm.scenarios_dir() + "/main.yaml", 10**19)


def test_warnings_and_diagnoses_are_in_python_words_too(readings):
    # Noise 100x the stated sigma: the model test fails and warns with its diagnosis.
    noisy = readings + np.random.default_rng(1).normal(0.0, 1e-3, readings.shape)
    with pytest.warns(RuntimeWarning) as caught:
        r = gpm.calibrate(noisy, gpm.load_robot(), sigma=1e-5)
    test = r.diagnostics["model_test"]
    assert not test["passed"] and test["diagnosis"].startswith("model test failed")
    texts = [test["diagnosis"], *r.diagnostics["notes"], *(str(w.message) for w in caught)]
    assert all(FLAG not in t for t in texts), texts


HOSTILE = [None, "x", "", 1.5, -1, 0, 10**30, -10**30, [1], ["la1"], {}, object(), float("nan"), float("inf"),
           True, 1j, np.int64(3), b"ml"]


def entry_points(readings):
    robot = gpm.load_robot()
    poses = [[216.5, 250.0]] * 12
    return {
        "calibrate": (lambda **k: gpm.calibrate(readings, robot, **k),
                      ["fix", "cost", "method", "sigma", "allow_rank_deficient", "budget", "seed", "true_xy", "t",
                       "tau_last", "tau_between", "encoder_bits", "static_model"]),
        "design": (lambda **k: gpm.design(**{"grid_step": 20.0, **k}),
                   ["robot", "count", "sigma", "fix", "criterion", "grid_step", "guard"]),
        "crb": (lambda **k: gpm.crb(robot, **({} if {"poses", "readings"} & set(k) else {"readings": readings}), **k),
                ["readings", "sigma", "fix", "poses"]),
        "pose_bounds": (lambda **k: gpm.pose_bounds(robot, **{"poses": poses, **k}), ["poses", "sigma", "fix"]),
        "Robot": (lambda **k: gpm.Robot(**k), ["geometry", "name"]),
        "load_robot": (lambda **k: gpm.load_robot(**k), ["path"]),
        "population_robot_scenario": (
            lambda **k: gpm.population_robot_scenario(**{"scenario_file": gpm.scenarios_dir() + "/main.yaml",
                                                         "seed": 1, **k}),
            ["scenario_file", "seed", "keep_effects"]),
    }


def test_hostile_values_of_every_keyword_raise_value_or_type_errors_naming_it(readings):
    # Each call answers, or raises gpm.InputError (a ValueError; gpm.InputTypeError also a TypeError)
    # whose message names the keyword first, or names a file; never a RuntimeError or a signature dump.
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, (call, keys) in entry_points(readings).items():
            for key in keys:
                for value in HOSTILE:
                    if key == "grid_step" and value in (1.5, 3):  # valid, and a fine grid takes minutes
                        continue
                    try:
                        call(**{key: value})
                    except gpm.InputError as e:
                        text = str(e)
                        assert "\n" not in text and "incompatible function arguments" not in text, (name, key, text)
                        if isinstance(e, TypeError):
                            assert text.startswith(key + ":"), (name, key, value, text)
