"""Each paper's data as typed constants, with the table it came from."""
