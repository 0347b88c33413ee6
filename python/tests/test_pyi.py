"""The type hints (.pyi) (python/rbsf/__init__.pyi) names what the module has, as the module has it."""

import pathlib
import subprocess
import sys

CHECK = pathlib.Path(__file__).with_name("pyi_check.py")
PYI = pathlib.Path(__file__).parents[1] / "rbsf" / "__init__.pyi"


def check(path):
    return subprocess.run([sys.executable, str(CHECK), str(path)], capture_output=True, text=True)


def test_the_type_hints_match_the_module():
    result = check(PYI)
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_check_finds_a_member_missing_and_a_wrong_default(tmp_path):
    text = PYI.read_text()
    missing = tmp_path / "missing.pyi"
    missing.write_text(text.replace("    def lower_bound(self) -> float:", "    def lower_bounds(self) -> float:", 1))
    result = check(missing)
    assert result.returncode == 1 and "Certificate.lower_bound is in rbsf, not in the .pyi" in result.stdout
    wrong = tmp_path / "wrong.pyi"
    wrong.write_text(text.replace('label: str = "<cell>"', 'label: str = "<file>"', 1))
    result = check(wrong)
    assert result.returncode == 1 and "label defaults to" in result.stdout
