-- The meshes table, as the SQLite catalog has it (sqlite_catalog.cpp),
-- with the invariants the code relies on written as constraints.
CREATE TABLE meshes (
  id        text    PRIMARY KEY CHECK (id ~ '^[0-9a-f]{12}$'),
  name      text    NOT NULL,
  source    text    NOT NULL,
  vertices  bigint  NOT NULL CHECK (vertices >= 0),
  faces     bigint  NOT NULL CHECK (faces >= 0),
  levels    integer NOT NULL CHECK (levels >= 0),
  packets   integer NOT NULL CHECK (packets >= 0),
  bytes     bigint  NOT NULL CHECK (bytes >= 0),
  container text    NOT NULL,
  sha256    text    NOT NULL UNIQUE CHECK (sha256 ~ '^[0-9a-f]{64}$'),
  created   bigint  NOT NULL  -- Unix seconds
);
CREATE INDEX meshes_by_created ON meshes (created, id);
