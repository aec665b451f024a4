"""The API as users and editors see it: every option of the command line as a keyword
with the same default, docstrings, and a stub that agrees with the module."""

import ast
import inspect
import pathlib
import re
import subprocess

import pdd


def cli_options(pdd_binary):
    text = subprocess.run([pdd_binary, "reconstruct", "--help"], check=True,
                          capture_output=True, text=True).stdout
    return set(re.findall(r"^\s+--([a-z][a-z-]+)", text, re.M))


# The command line's own output options; Python returns the mesh and stats instead,
# and has write_mesh(ascii=) and the progress callback.
CLI_ONLY = {"output", "stats", "quiet", "ascii", "help", "domain-out", "save-iterations"}


def test_every_command_line_option_is_a_keyword_with_its_default(pdd_binary):
    params = inspect.signature(pdd.reconstruct).parameters
    renamed = {"normals": "normals_mode"}  # `normals` is the array of normals
    for option in cli_options(pdd_binary) - CLI_ONLY:
        assert renamed.get(option, option.replace("-", "_")) in params, option
    assert "domain_out" in params and "save_iterations" in params
    assert params["solver"].default == "ssd"
    assert params["iterations"].default == 12
    assert params["enlarge_ratio"].default == 1.4
    assert params["target_edge"].default is None  # derived from the input
    assert params["no_cleanup"].default is False


def test_help_shows_the_options():
    doc = pdd.reconstruct.__doc__
    for name in ("target_edge", "value_weight", "max_memory", "seed", "progress"):
        assert name in doc
    for function in (pdd.read_points, pdd.read_mesh, pdd.write_mesh, pdd.quality, pdd.compare):
        assert function.__doc__ and len(function.__doc__) > 40


def test_the_stub_agrees_with_the_module():
    stub = pathlib.Path(pdd.__file__).with_name("__init__.pyi")
    tree = ast.parse(stub.read_text())
    functions = {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}
    assert set(pdd.__all__) - {"Cancelled", "Mesh", "PointCloud", "Progress"} <= set(functions)
    stub_reconstruct = functions["reconstruct"].args
    names = [a.arg for a in stub_reconstruct.kwonlyargs]
    defaults = [ast.literal_eval(d) for d in stub_reconstruct.kw_defaults]
    params = inspect.signature(pdd.reconstruct).parameters
    runtime = [(n, p.default) for n, p in params.items() if p.kind == p.KEYWORD_ONLY]
    assert list(zip(names, defaults)) == runtime
