/**
 * The robot description an MCAP carries for Foxglove's and Lichtblick's 3D panel: the URDF text
 * with every `<mesh filename>` replaced by a `data:` URI that holds the mesh file itself.
 *
 * Why data URIs: the 3D panel loads a URDF from a topic (`/{arm}/robot_description`, a message
 * with a string `data`) and fetches each mesh by its URL. From a recording there is nothing to resolve
 * `package://` or a relative path against (Lichtblick sends `package://` to a live connection's
 * asset service, or to the desktop app's ROS package path; a file has neither, and MCAP
 * attachments are not read as assets), while a `data:` URL goes through the browser's own fetch
 * in both apps and with any data source, its media type choosing the mesh loader. So the file
 * opens with no setup and no robot folder beside it. Pure: the mesh bytes come from `read`.
 */
import { IMPORT_MESH_KINDS, meshRefs, rewriteMeshPaths, type ImportMeshKind } from '@armtwin/robot';

/** A mesh the description embeds. */
export interface DescriptionMesh {
  /** As the URDF names it (`meshes/base.stl`, `package://pkg/meshes/base.stl`). */
  filename: string;
  mediaType: string;
  bytes: Uint8Array;
}

export interface RobotDescription {
  /** The URDF with its meshes inline (what the robot description topic carries). */
  urdf: string;
  /** Each embedded mesh once. */
  meshes: DescriptionMesh[];
  /** Meshes that could not be embedded, each with why; left as the URDF names them. */
  missing: string[];
}

/**
 * The media type of each mesh kind a robot folder holds (the kinds the HUD and the import
 * take), as Foxglove's and Lichtblick's mesh loaders recognise them.
 */
const MEDIA_TYPES: Record<ImportMeshKind, string> = {
  stl: 'model/stl',
  dae: 'model/vnd.collada+xml',
  obj: 'model/obj',
};

/** The media type of a mesh file by its extension, or undefined for another kind. */
export function meshMediaType(filename: string): string | undefined {
  const ext = /\.([a-z0-9]+)$/i.exec(filename)?.[1]?.toLowerCase() ?? '';
  return (IMPORT_MESH_KINDS as readonly string[]).includes(ext)
    ? MEDIA_TYPES[ext as ImportMeshKind]
    : undefined;
}

/** A `data:` URI of `bytes` (base64). */
export const dataUri = (mediaType: string, bytes: Uint8Array): string =>
  `data:${mediaType};base64,${Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength).toString('base64')}`;

/**
 * `urdf` with every link mesh inline. `read(filename)` returns a mesh's bytes or throws saying
 * why (the caller resolves names against the robot folder).
 */
export function selfContainedUrdf(
  urdf: string,
  read: (filename: string) => Uint8Array,
): RobotDescription {
  const meshes: DescriptionMesh[] = [];
  const missing: string[] = [];
  const uris = new Map<string, string>();
  for (const { filename } of meshRefs(urdf)) {
    if (filename.startsWith('data:')) continue;
    const mediaType = meshMediaType(filename);
    if (!mediaType) {
      missing.push(`${filename}: not a mesh kind armtwin reads (${IMPORT_MESH_KINDS.join(', ')})`);
      continue;
    }
    try {
      const bytes = read(filename);
      meshes.push({ filename, mediaType, bytes });
      uris.set(filename, dataUri(mediaType, bytes));
    } catch (err) {
      missing.push(`${filename}: ${(err as Error).message}`);
    }
  }
  return { urdf: rewriteMeshPaths(urdf, (f) => uris.get(f) ?? null), meshes, missing };
}
