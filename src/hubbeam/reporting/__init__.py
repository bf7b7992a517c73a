"""Documents and products: Markdown documents from the templates (package data ``templates/``),
number formatting, the registry of products a configuration asks for, the source files each
workflow script depends on and the description of the results archive (RO-Crate)."""
