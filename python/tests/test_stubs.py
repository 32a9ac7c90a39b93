"""The type stubs say what the functions take: every keyword a stub names is an option of the
function, with the command line's default."""

import ast
from pathlib import Path

import bumpmap
from bumpmap import _bumpmap

STUB = Path(bumpmap.__file__).with_name("__init__.pyi")


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
    return str(stub_value) == cli_default


def test_stub_defaults_are_the_cli_defaults():
    functions = stub_functions()
    checked = 0
    for name in ["normal_map", "mip_chain", "height_mips", "horizon_maps", "read_height_field", "write_texture", "tangents", "render", "compare", "height_from_normals"]:
        node = functions[name]
        options = {o[0]: o for o in _bumpmap.options(name)}
        for arg, default in zip(node.args.kwonlyargs, node.args.kw_defaults):
            assert arg.arg in options, f"{name}({arg.arg}=): not an option of the command"
            _, cli_default, _, _, is_flag = options[arg.arg]
            value = ast.literal_eval(default)
            assert same_default(value, cli_default, is_flag), f"{name}({arg.arg}={value!r}): the CLI's is {cli_default!r}"
            checked += 1
        if name not in ("render", "compare"):
            # The short lists are complete.
            assert {a.arg for a in node.args.kwonlyargs} == set(options), name
    assert checked > 30
