-- Originals kept, containers re-encoded (sqlite/0002_originals.sql).
-- meshes: the container's format version (0: not recorded yet), the
-- original it was made from ('' : none) and the encoder settings.
ALTER TABLE meshes ADD COLUMN format_version integer NOT NULL DEFAULT 0
  CHECK (format_version >= 0);
ALTER TABLE meshes ADD COLUMN original text NOT NULL DEFAULT ''
  CHECK (original = '' OR original ~ '^[0-9a-f]{64}$');
ALTER TABLE meshes ADD COLUMN settings text NOT NULL DEFAULT '';
-- Ids no longer come from the container: two meshes may share one (the
-- same bytes made under two settings that do not change them).
ALTER TABLE meshes DROP CONSTRAINT meshes_sha256_key;
CREATE INDEX meshes_by_sha256 ON meshes (sha256);
CREATE INDEX meshes_by_original ON meshes (original);
-- An original: its manifest's digest, main file and format, total bytes.
CREATE TABLE originals (
  digest  text   PRIMARY KEY CHECK (digest ~ '^[0-9a-f]{64}$'),
  main    text   NOT NULL,
  format  text   NOT NULL,
  bytes   bigint NOT NULL CHECK (bytes >= 0),
  created bigint NOT NULL  -- Unix seconds
);
-- Its files; each is the blob STORE/originals/<sha256>.
CREATE TABLE original_files (
  original text   NOT NULL REFERENCES originals (digest) ON DELETE CASCADE,
  name     text   NOT NULL,
  sha256   text   NOT NULL CHECK (sha256 ~ '^[0-9a-f]{64}$'),
  bytes    bigint NOT NULL CHECK (bytes >= 0),
  PRIMARY KEY (original, name)
);
CREATE INDEX original_files_by_sha256 ON original_files (sha256);
-- Containers replaced by a re-encode, kept for readers that may still
-- open them until they expire.
CREATE TABLE retired_containers (
  container text   PRIMARY KEY,
  retired   bigint NOT NULL  -- Unix seconds
);
-- Bumped by every insert, delete and container swap: servers poll it.
CREATE TABLE catalog_generation (
  one        integer PRIMARY KEY CHECK (one = 1),
  generation bigint  NOT NULL
);
INSERT INTO catalog_generation VALUES (1, 0);
