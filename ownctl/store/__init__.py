"""The persistent store: SQLAlchemy 2 models, the repository (:class:`repo.Tx`), engine setup and
Alembic migrations. The only package that imports SQLAlchemy or Alembic; import its modules
(``ownctl.store.engine``, ``ownctl.store.repo``) explicitly, so ``import ownctl.store`` stays cheap."""
