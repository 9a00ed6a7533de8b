"""The workbench around the library: claims against the papers (:mod:`~springlab.workbench.claims`), Markdown
tables (:mod:`~springlab.tables`), figures (:mod:`~springlab.workbench.plotting`), the notebook runner (:mod:`~springlab.workbench.notebooks`),
the site and report (:mod:`~springlab.workbench.site`) and the command line (:mod:`~springlab.workbench.cli`)."""
