"""Reading and checking spec files: safe YAML loading, the schema, cross-references."""
