"""Job writers: the biaxial, footing and column-collapse jobs of jobs/ and docs/data."""
