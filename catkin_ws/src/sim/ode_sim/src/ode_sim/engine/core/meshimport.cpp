#include "meshimport.h"

#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <stdexcept>

namespace ode_sim {

namespace {

void copyColor(const aiMaterial* m, const char* key, unsigned type, unsigned idx,
               std::array<double, 4>& out, bool& has) {
  aiColor4D c;
  if (aiGetMaterialColor(m, key, type, idx, &c) == AI_SUCCESS) {
    out = {c.r, c.g, c.b, c.a};
    has = true;
  }
}

void walk(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, ImportedScene& out) {
  const aiMatrix4x4 m = parent * node->mTransformation;
  aiMatrix3x3 nm(m);
  nm.Inverse().Transpose();
  for (unsigned k = 0; k < node->mNumMeshes; ++k) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[k]];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points, lines
    ImportedMesh im;
    im.node = node->mName.C_Str();
    im.name = mesh->mName.C_Str();
    im.material = static_cast<int>(mesh->mMaterialIndex);
    const unsigned n = mesh->mNumVertices;
    im.positions.reserve(3 * n);
    im.normals.reserve(3 * n);
    for (unsigned i = 0; i < n; ++i) {
      const aiVector3D p = m * mesh->mVertices[i];
      im.positions.insert(im.positions.end(), {p.x, p.y, p.z});
      aiVector3D q = mesh->mNormals ? nm * mesh->mNormals[i] : aiVector3D(0, 0, 1);
      const ai_real len = q.Length();
      if (len > 0 && std::isfinite(len)) q /= len;
      im.normals.insert(im.normals.end(), {static_cast<float>(q.x), static_cast<float>(q.y),
                                           static_cast<float>(q.z)});
    }
    if (mesh->mTextureCoords[0]) {
      im.uvs.reserve(2 * n);
      for (unsigned i = 0; i < n; ++i)
        im.uvs.insert(im.uvs.end(), {static_cast<float>(mesh->mTextureCoords[0][i].x),
                                     static_cast<float>(mesh->mTextureCoords[0][i].y)});
    }
    im.faces.reserve(3 * mesh->mNumFaces);
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned j = 0; j < 3; ++j) im.faces.push_back(static_cast<int32_t>(face.mIndices[j]));
    }
    if (!im.faces.empty()) out.meshes.push_back(std::move(im));
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) walk(scene, node->mChildren[c], m, out);
}

}  // namespace

ImportedScene importScene(const std::string& path) {
  Assimp::Importer importer;
  // the up axis is turned to Z by the caller (Gazebo's rule), not to Y as assimp would
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_SortByPType | aiProcess_GenNormals |
                         aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (!scene) {
    std::string why = importer.GetErrorString();
    for (char& ch : why)
      if (ch == '\n' || ch == '\r') ch = ' ';
    throw std::runtime_error(why.empty() ? std::string("assimp cannot read it") : why);
  }
  ImportedScene out;
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    const aiMaterial* m = scene->mMaterials[i];
    ImportedMaterial im;
    aiString s;
    if (m->Get(AI_MATKEY_NAME, s) == AI_SUCCESS) im.name = s.C_Str();
    copyColor(m, AI_MATKEY_COLOR_DIFFUSE, im.diffuse, im.has_diffuse);
    copyColor(m, AI_MATKEY_COLOR_AMBIENT, im.ambient, im.has_ambient);
    copyColor(m, AI_MATKEY_COLOR_EMISSIVE, im.emissive, im.has_emissive);
    copyColor(m, AI_MATKEY_COLOR_SPECULAR, im.specular, im.has_specular);
    float v = 1.0f;
    if (m->Get(AI_MATKEY_OPACITY, v) == AI_SUCCESS && std::isfinite(v)) im.opacity = v;
    if (m->Get(AI_MATKEY_SHININESS, v) == AI_SUCCESS && std::isfinite(v)) im.shininess = v;
    if (m->GetTextureCount(aiTextureType_DIFFUSE) > 0 &&
        m->GetTexture(aiTextureType_DIFFUSE, 0, &s) == AI_SUCCESS)
      im.texture = s.C_Str();
    out.materials.push_back(std::move(im));
  }
  if (scene->mRootNode) walk(scene, scene->mRootNode, aiMatrix4x4(), out);
  return out;
}

}  // namespace ode_sim
