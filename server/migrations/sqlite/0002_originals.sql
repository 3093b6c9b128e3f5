-- Originals kept, containers re-encoded (postgres/0002_originals.sql).
-- meshes: the container's format version (0: not recorded yet), the
-- original it was made from ('' : none) and the encoder settings.
ALTER TABLE meshes ADD COLUMN format_version INTEGER NOT NULL DEFAULT 0;
ALTER TABLE meshes ADD COLUMN original TEXT NOT NULL DEFAULT '';
ALTER TABLE meshes ADD COLUMN settings TEXT NOT NULL DEFAULT '';
CREATE INDEX meshes_by_original ON meshes (original);
-- An original: its manifest's digest, main file and format, total bytes.
CREATE TABLE originals (
  digest TEXT PRIMARY KEY NOT NULL,
  main TEXT NOT NULL,
  format TEXT NOT NULL,
  bytes INTEGER NOT NULL,
  created INTEGER NOT NULL
);
-- Its files; each is the blob STORE/originals/<sha256>.
CREATE TABLE original_files (
  original TEXT NOT NULL REFERENCES originals (digest) ON DELETE CASCADE,
  name TEXT NOT NULL,
  sha256 TEXT NOT NULL,
  bytes INTEGER NOT NULL,
  PRIMARY KEY (original, name)
);
CREATE INDEX original_files_by_sha256 ON original_files (sha256);
-- Containers replaced by a re-encode, kept for readers that may still
-- open them until they expire.
CREATE TABLE retired_containers (
  container TEXT PRIMARY KEY NOT NULL,
  retired INTEGER NOT NULL
);
-- Bumped by every insert, delete and container swap: servers poll it.
CREATE TABLE catalog_generation (
  one INTEGER PRIMARY KEY NOT NULL CHECK (one = 1),
  generation INTEGER NOT NULL
);
INSERT INTO catalog_generation VALUES (1, 0);
