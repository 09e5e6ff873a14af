// SPDX-License-Identifier: GPL-3.0-or-later
// Surface import through assimp (the only file that includes it): see io/mesh/cad_mesh.hpp.
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unordered_map>

#include "engine/errors.hpp"
#include "io/mesh/cad_mesh.hpp"

namespace femdem {

namespace {

// Appends the triangles of `node` and its children, with the node transforms applied (glTF,
// 3MF, COLLADA and FBX place their meshes through a node hierarchy; STL, OBJ, PLY and OFF have
// only the identity root).
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, double scale,
             std::vector<Vec3>& points, std::vector<std::array<std::int32_t, 3>>& triangles,
             CadImportInfo& info, const std::string& path) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const std::size_t first = points.size();
    info.input_vertices += mesh.mNumVertices;
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      const Vec3 x(scale * static_cast<double>(p.x), scale * static_cast<double>(p.y),
                   scale * static_cast<double>(p.z));
      if (!x.allFinite())
        throw InputError("not a mesh: vertex " + std::to_string(v) + " of mesh '" +
                             mesh.mName.C_Str() + "' has a non-finite coordinate",
                         path);
      points.push_back(x);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {  // points and lines (polygons were triangulated)
        ++info.skipped_primitives;
        continue;
      }
      std::array<std::int32_t, 3> t;
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices)
          throw InputError("not a mesh: face " + std::to_string(f) + " of mesh '" +
                               mesh.mName.C_Str() + "' refers to vertex " +
                               std::to_string(face.mIndices[k]) + " of " +
                               std::to_string(mesh.mNumVertices),
                           path);
        t[k] = static_cast<std::int32_t>(first + face.mIndices[k]);
      }
      triangles.push_back(t);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    collect(scene, *node.mChildren[c], transform, scale, points, triangles, info, path);
}

// Merges points closer than `tol` (the first point of a cluster represents it) with a hash
// grid of cell size tol, so each point looks at its own and the 26 neighbouring cells. Returns
// the new index of every point; `points` is replaced by the representatives, in input order.
std::vector<std::int32_t> merge_points(std::vector<Vec3>& points, double tol) {
  struct KeyHash {
    std::size_t operator()(const std::array<std::int64_t, 3>& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (std::int64_t v : k) h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::int32_t>, KeyHash> grid;
  grid.reserve(points.size());
  std::vector<Vec3> kept;
  std::vector<std::int32_t> index(points.size());
  const double tol2 = tol * tol;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& x = points[i];
    const std::array<std::int64_t, 3> cell = {static_cast<std::int64_t>(std::floor(x[0] / tol)),
                                              static_cast<std::int64_t>(std::floor(x[1] / tol)),
                                              static_cast<std::int64_t>(std::floor(x[2] / tol))};
    std::int32_t found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          const auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == grid.end()) continue;
          for (std::int32_t j : it->second)
            if ((kept[j] - x).squaredNorm() <= tol2) {
              found = j;
              break;
            }
        }
    if (found < 0) {
      found = static_cast<std::int32_t>(kept.size());
      kept.push_back(x);
      grid[cell].push_back(found);
    }
    index[i] = found;
  }
  points = std::move(kept);
  return index;
}

}  // namespace

bool cad_format_supported(const std::string& extension) {
  return !extension.empty() && Assimp::Importer().IsExtensionSupported(extension);
}

std::string cad_extensions() {
  // The common ones; assimp knows about 70 more (mostly game and scene formats).
  return ".stl, .obj, .ply, .off, .gltf, .glb, .3mf, .dae, .fbx and the other formats assimp "
         "reads";
}

TriangleSurface import_surface(const std::string& path, double scale, double merge_tolerance,
                               CadImportInfo* info_out) {
  CadImportInfo info;
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw InputError("scale must be a positive number", path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("cannot read the surface file: it does not exist or is not a file", path);

  Assimp::Importer importer;
  // Only the geometry is needed: no normals, colours, textures, materials or animations.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_TEXCOORDS |
                                  aiComponent_ANIMATIONS | aiComponent_TEXTURES |
                                  aiComponent_LIGHTS | aiComponent_CAMERAS | aiComponent_MATERIALS);
  const aiScene* scene = importer.ReadFile(path, aiProcess_RemoveComponent | aiProcess_Triangulate);
  if (!scene) {
    std::string why = importer.GetErrorString();
    while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
    throw InputError("not a mesh: assimp says: " + (why.empty() ? std::string("(no reason)") : why),
                     path);
  }
  const std::string ext = std::filesystem::path(path).extension().string();
  const std::size_t importer_index = importer.GetImporterIndex(ext.c_str());
  if (const aiImporterDesc* d = importer.GetImporterInfo(importer_index); d && d->mName)
    info.format = d->mName;
  info.meshes = scene->mNumMeshes;

  TriangleSurface s;
  if (scene->mRootNode)
    collect(*scene, *scene->mRootNode, aiMatrix4x4(), scale, s.points, s.triangles, info, path);
  info.input_triangles = static_cast<std::int64_t>(s.triangles.size());
  if (s.triangles.empty()) {
    std::string msg = "empty: no triangles";
    if (info.skipped_primitives > 0)
      msg += " (only " + std::to_string(info.skipped_primitives) + " points or lines)";
    else if (scene->mNumMeshes == 0)
      msg += " (the file holds no meshes)";
    throw InputError(msg, path);
  }

  // Merge duplicate vertices: STL stores every triangle's corners separately, and other formats
  // split vertices at normal or texture seams.
  Vec3 lo = s.points[0], hi = s.points[0];
  for (const Vec3& x : s.points) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double diag = (hi - lo).norm();
  if (!(diag > 0.0))
    throw InputError(
        "degenerate: all " + std::to_string(s.points.size()) + " vertices are at the same point",
        path);
  const std::vector<std::int32_t> index =
      merge_points(s.points, std::max(merge_tolerance, 1e-15) * diag);
  for (auto& t : s.triangles)
    for (auto& v : t) v = index[static_cast<std::size_t>(v)];
  info.merged_vertices = static_cast<std::int64_t>(s.points.size());
  if (info_out) *info_out = std::move(info);
  return s;
}

}  // namespace femdem
