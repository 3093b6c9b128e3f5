-- The meshes table (postgres/0001_init.sql has the same with constraints).
-- IF NOT EXISTS: catalogs made before the schema was versioned have it.
CREATE TABLE IF NOT EXISTS meshes (
  id TEXT PRIMARY KEY NOT NULL,
  name TEXT NOT NULL,
  source TEXT NOT NULL,
  vertices INTEGER NOT NULL,
  faces INTEGER NOT NULL,
  levels INTEGER NOT NULL,
  packets INTEGER NOT NULL,
  bytes INTEGER NOT NULL,
  container TEXT NOT NULL,
  sha256 TEXT NOT NULL,
  created INTEGER NOT NULL
);
CREATE INDEX IF NOT EXISTS meshes_by_created ON meshes (created, id);
