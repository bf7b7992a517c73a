"""The results as files: the variables a result holds, writing and reading datasets, the reader's
accessors, provenance, where every result and log goes, and the measures taken from results."""
