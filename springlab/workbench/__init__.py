"""The workbench around the library: claims against the papers (:mod:`.claims`), Markdown
tables (:mod:`.tables`), figures (:mod:`.plotting`), the notebook runner (:mod:`.notebooks`),
the site and report (:mod:`.site`) and the command line (:mod:`.cli`)."""
