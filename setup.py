"""Packaging hook: ship the top-level Alembic folder ``migrations/`` in the wheel as ``ownctl/_migrations``.

Everything else is declared in pyproject.toml. ``packages.find`` cannot map a folder outside the
package tree, so build_py copies it; ``ownctl.store.migrate`` finds the copy in an installed wheel
and falls back to ``migrations/`` in a development (editable) checkout.
"""

from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

MIGRATIONS = Path(__file__).resolve().parent / "migrations"


class BuildPyWithMigrations(build_py):
    """build_py that also copies migrations/ (env.py, script.py.mako, versions/*.py)."""

    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            return  # an editable install reads migrations/ in place
        if not (MIGRATIONS / "env.py").is_file():
            raise SystemExit(f"cannot build ownctl: {MIGRATIONS} is missing (is MANIFEST.in grafting it?)")
        target = Path(self.build_lib) / "ownctl" / "_migrations"
        for source in sorted(MIGRATIONS.rglob("*")):
            if source.is_file() and "__pycache__" not in source.parts and source.suffix != ".pyc":
                dest = target / source.relative_to(MIGRATIONS)
                self.mkpath(str(dest.parent))
                self.copy_file(str(source), str(dest), preserve_mode=False)


setup(cmdclass={"build_py": BuildPyWithMigrations})
