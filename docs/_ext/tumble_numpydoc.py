"""numpydoc's docstring template compiled once per build, not once per docstring.

numpydoc (1.11: ``numpydoc.docscrape_sphinx.get_doc_object``) makes a new Jinja environment and
compiles its ``numpydoc_docstring.rst`` template for every docstring it renders: 4,056 times in
tumble's build, 80.5 -> 71.4 CPU-s of the whole build when compiled once (``-j 1``, measured on
2026-11-29). numpydoc's ``setup`` takes the function that makes its docstring objects as an
argument (``get_doc_object_``) and keeps it in a module global; this extension puts there the same
function with the template made once for each builder, from the same loader (Sphinx's template
loader over the project's ``templates_path`` and numpydoc's own templates). The pages are the
same, byte for byte.

Written by hand because numpydoc has no option to keep its template. Where numpydoc no longer has
the names used here, numpydoc is left as it is (the build is only slower).
"""

from __future__ import annotations

import os
from typing import Any

from sphinx.application import Sphinx


def setup(app: Sphinx) -> dict[str, Any]:
    try:
        from jinja2 import FileSystemLoader
        from jinja2.sandbox import SandboxedEnvironment
        from numpydoc import docscrape, docscrape_sphinx, numpydoc
        from sphinx.jinja2glue import BuiltinTemplateLoader

        parts = (docscrape.get_doc_object, docscrape_sphinx.SphinxClassDoc, docscrape_sphinx.SphinxFunctionDoc,
                 docscrape_sphinx.SphinxObjDoc, numpydoc.get_doc_object)
    except (ImportError, AttributeError):
        return {"parallel_read_safe": True, "parallel_write_safe": True}
    make, class_doc, func_doc, obj_doc, _ = parts
    dirs = [os.path.join(os.path.dirname(docscrape_sphinx.__file__), "templates")]
    templates: dict[int, Any] = {}  # id(builder) -> the compiled template

    def template(builder: Any) -> Any:
        if id(builder) not in templates:  # numpydoc's loaders: Sphinx's with a builder, else its own folder
            loader = FileSystemLoader(dirs) if builder is None else BuiltinTemplateLoader()
            if builder is not None:
                loader.init(builder, dirs=dirs)
            templates[id(builder)] = SandboxedEnvironment(loader=loader).get_template("numpydoc_docstring.rst")
        return templates[id(builder)]

    def get_doc_object(obj: Any, what: str | None = None, doc: str | None = None, config: dict | None = None,
                       builder: Any = None) -> Any:
        config = {} if config is None else config
        config["template"] = template(builder)
        return make(obj, what=what, doc=doc, config=config, class_doc=class_doc, func_doc=func_doc, obj_doc=obj_doc)

    numpydoc.get_doc_object = get_doc_object  # what numpydoc's setup(app, get_doc_object_=...) sets
    return {"parallel_read_safe": True, "parallel_write_safe": True}
