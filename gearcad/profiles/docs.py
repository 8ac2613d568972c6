"""Field docstrings as the JSON Schema's descriptions, read only when the schema is made.

A field is documented by the string that follows it in its class body (the attribute
docstring convention).  Pydantic can collect them itself (``use_attribute_docstrings``), but
then parses every model's source at import — a tenth of a second on each run that never
writes a schema.  Here they are read on demand and given to the models before the schema is
generated.
"""

from __future__ import annotations

import ast
import inspect
import textwrap

from pydantic import BaseModel

__all__ = ["field_docstrings", "document_fields"]


def field_docstrings(cls: type) -> dict[str, str]:
    """``{field: docstring}`` for the fields written in ``cls``'s own body."""
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(cls)))
    except OSError:  # no source installed (a zipped or frozen gearcad): no descriptions
        return {}
    body = tree.body[0].body
    docs = {}
    for node, after in zip(body, body[1:]):
        if (
            isinstance(node, ast.AnnAssign)
            and isinstance(node.target, ast.Name)
            and isinstance(after, ast.Expr)
            and isinstance(after.value, ast.Constant)
            and isinstance(after.value.value, str)
        ):
            docs[node.target.id] = inspect.cleandoc(after.value.value)
    return docs


def document_fields(models: list[type[BaseModel]]) -> None:
    """Give every field of ``models`` without a description its docstring, and rebuild the
    models (twice: a model that holds another takes the other's rebuilt schema)."""
    for cls in models:
        docs: dict[str, str] = {}
        for base in reversed(cls.__mro__):
            if isinstance(base, type) and issubclass(base, BaseModel) and base.__module__.startswith("gearcad."):
                docs.update(field_docstrings(base))
        for name, field in cls.model_fields.items():
            if field.description is None and name in docs:
                field.description = docs[name]
    for _ in range(2):
        for cls in models:
            cls.model_rebuild(force=True)
