"""The type stubs say what the functions take: every option of each function, with the command
line's default; each closed set as a Literal generated from the native module (so from the Rust
definitions); a type checker accepts typical calls and rejects misspelt ones. And the functions
say it at run time: `inspect.signature` lists every keyword with its default."""

import ast
import importlib.util
import inspect
import subprocess
import sys
from pathlib import Path

import bumpmap
from bumpmap import _bumpmap

STUB = Path(bumpmap.__file__).with_name("__init__.pyi")
# Every function that takes the command line's options.
FUNCTIONS = ["normal_map", "mip_chain", "height_mips", "write_heights", "horizon_maps", "roughness_map", "lean_moments",
             "read_height_field", "write_texture", "tangents", "render", "compare", "height_from_normals", "bake", "blend_normals"]


def stub_functions():
    tree = ast.parse(STUB.read_text())
    return {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}


def same_default(stub_value, cli_default, is_flag):
    if is_flag:
        return stub_value is False
    if cli_default is None:
        return stub_value is None
    if isinstance(stub_value, (int, float)) and not isinstance(stub_value, bool):
        return float(cli_default) == float(stub_value)
    if isinstance(stub_value, tuple):
        return tuple(float(v) for v in stub_value) == tuple(float(p) for p in cli_default.split(","))
    return str(stub_value) == cli_default


def test_stub_defaults_are_the_cli_defaults():
    functions = stub_functions()
    checked = 0
    for name in FUNCTIONS:
        node = functions[name]
        options = {o[0]: o for o in _bumpmap.options(name)}
        own = bumpmap._OWN_KEYWORDS.get(name, [])
        for arg, default in zip(node.args.kwonlyargs, node.args.kw_defaults):
            if arg.arg in own:
                assert ast.literal_eval(default) is None, f"{name}({arg.arg}=): None by default"
                continue
            assert arg.arg in options, f"{name}({arg.arg}=): not an option of the command"
            _, cli_default, _, _, is_flag = options[arg.arg]
            value = ast.literal_eval(default)
            assert same_default(value, cli_default, is_flag), f"{name}({arg.arg}={value!r}): the CLI's is {cli_default!r}"
            checked += 1
        assert {a.arg for a in node.args.kwonlyargs} == set(options) | set(own), f"{name}: every option, and no other"
    assert checked > 80


REPO = Path(__file__).resolve().parents[2]


def stubs_script():
    spec = importlib.util.spec_from_file_location("python_stubs", REPO / "scripts" / "python_stubs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_generated_parts_are_the_native_modules():
    script = stubs_script()
    made = script.block()
    assert "_Technique = Literal[" in made and '"height-exact"' in made
    text = STUB.read_text()
    assert script.current(text) == made, "run scripts/python_stubs.py --write"
    # Every function's options are generated, none written by hand.
    for name in FUNCTIONS:
        assert f"# BEGIN options of {name}\n" in text, f"{name}: its options are not generated"
    assert script.made(text) == text, "run scripts/python_stubs.py --write"


def test_a_new_option_reaches_the_stub_through_the_generator(monkeypatch):
    # The generator writes what the native module reports: an option it reports is in the stub.
    script = stubs_script()
    real_options, real_kinds = _bumpmap.options, _bumpmap.option_kinds
    extra = ("exposure", "1.5", "A brand-new option.", [], False)
    monkeypatch.setattr(script._bumpmap, "options", lambda f: real_options(f) + ([extra] if f == "render" else []))
    monkeypatch.setattr(script._bumpmap, "option_kinds",
                        lambda f: real_kinds(f) + ([("exposure", "number")] if f == "render" else []))
    made = script.made(STUB.read_text())
    assert "    exposure: float = 1.5,\n    # END options of render" in made


def test_every_option_with_a_closed_set_is_typed_by_it():
    functions = stub_functions()
    for (function, option), (alias, _choices) in stubs_script().aliases().items():
        arg = next(a for a in functions[function].args.kwonlyargs if a.arg == option)
        assert alias in ast.unparse(arg.annotation), f"{function}({option}=): {ast.unparse(arg.annotation)}, not {alias}"


def test_signatures_list_every_keyword_with_its_default():
    for name in FUNCTIONS:
        params = inspect.signature(getattr(bumpmap, name)).parameters
        for option, default, _help, _choices, flag in _bumpmap.options(name):
            p = params[option]
            assert p.kind is inspect.Parameter.KEYWORD_ONLY, (name, option)
            assert same_default(p.default, default, flag), f"{name}({option}={p.default!r}): the CLI's is {default!r}"
    render = inspect.signature(bumpmap.render).parameters
    assert render["technique"].default == "kilgard" and render["size"].default == 512
    assert render["progress"].default is None and inspect.signature(bumpmap.compare).parameters["progress"].default is None
    assert "progress" not in inspect.signature(bumpmap.Renderer.prepare).parameters
    assert list(inspect.signature(bumpmap.tangents).parameters)[:4] == ["positions", "normals", "uvs", "indices"]


TYPICAL = """
import numpy as np
import bumpmap

heights = bumpmap.read_height_field("bricks@64")
normals = bumpmap.normal_map(heights, scale=6, kernel="sobel3", y_convention="directx")
chain = bumpmap.mip_chain(heights, bits=16)
paths = bumpmap.write_texture("n.ktx2", chain, format="bc7")
first: str = paths[0].name
back = bumpmap.read_texture(paths[0])
levels = back["levels"]
image = bumpmap.render(technique="pom", backend="auto", size=64, eye=(0, -6, 3), light=["4,0,3", "dir:-1,0,1"])
lit = bumpmap.render(light=(1.0, 2.0, 3.0), specular_filter="lean", filter="nearest")
ok: bool = bool(image.any())
warm = bumpmap.render(light=[{"position": (4, 0, 3), "color": (1, 0.6, 0.4)}, {"direction": (-1, 0, 1)}],
                      attenuation=(1, 0.2, 0.05), torus_radii=(2.5, 0.5), tessellation=(64, 32))
results = bumpmap.compare(techniques=["kilgard", "single-pass"], studies="none")
seen: list[tuple[int, int]] = []
reference = bumpmap.render(technique="reference", progress=lambda done, total: seen.append((done, total)))
rough = bumpmap.roughness_map(heights, roughness=0.3, roughness_layout="gltf")
moments, mxy_j = bumpmap.lean_moments(heights)
first_moment: float = float(moments[0][0, 0, 0])
"""

# Each line must be refused by the type checker: (line, what it gets wrong).
WRONG = [
    ('bumpmap.render(technique="kilgrad")', "a misspelt technique"),
    ('bumpmap.write_texture("n.dds", np.zeros((4, 4, 4), np.uint8), format="BC5")', "a format in the wrong case"),
    ('bumpmap.normal_map(bumpmap.read_height_field("bricks"), kernel="sobel")', "a kernel that does not exist"),
    ('bumpmap.render(size="64")', "a size as text"),
    ('bumpmap.render(no_such_option=1)', "an option that does not exist"),
    ('x: str = bumpmap.write_texture("n.png", np.zeros((4, 4, 4), np.uint8))[0]', "paths are not str"),
    ('bumpmap.render(progress=3)', "a progress that is not a function"),
    ('bumpmap.render(eye="0,-6,3")', "a vector as text"),
    ('bumpmap.render(light={"colour": (1, 1, 1)})', "a light with a key that does not exist"),
    ('bumpmap.roughness_map(bumpmap.read_height_field("bricks"), roughness_layout="orm")', "a layout that does not exist"),
]


def test_a_type_checker_accepts_typical_calls_and_refuses_wrong_ones(tmp_path):
    # scripts/test_python.sh installs mypy: missing, the test fails, not skips.
    import mypy  # noqa: F401

    (tmp_path / "typical.py").write_text(TYPICAL)
    wrong = "import numpy as np\nimport bumpmap\n" + "\n".join(line for line, _ in WRONG) + "\n"
    (tmp_path / "wrong.py").write_text(wrong)

    def mypy(file):
        done = subprocess.run([sys.executable, "-m", "mypy", "--no-incremental", "--strict", "--no-error-summary",
                               "--cache-dir", str(tmp_path / "cache"), str(file)],
                              capture_output=True, text=True, cwd=tmp_path)
        return done.stdout + done.stderr

    assert mypy("typical.py").strip() == "", "typical calls refused:\n" + mypy("typical.py")
    out = mypy("wrong.py")
    for k, (line, what) in enumerate(WRONG):
        assert f"wrong.py:{k + 3}:" in out, f"{what} passed the type checker: {line}\n{out}"
