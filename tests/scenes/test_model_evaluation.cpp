// Node animation, skinning and morph targets against values computed by hand, on tiny aiScenes
// built in memory (so every number is known) and on Khronos' SimpleMorph.
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "scenes/model_animation.h"
#include "scenes/model_import.h"
#include "tests/scenes/model_test_support.h"
#include "util/input_error.h"
#include "util/warning.h"

namespace kinray {
namespace {

using testing::kSharedModels;

constexpr double kEps = 1e-9;

aiMatrix4x4 translation(double x, double y, double z) {
  aiMatrix4x4 m;
  aiMatrix4x4::Translation(aiVector3D(ai_real(x), ai_real(y), ai_real(z)), m);
  return m;
}

aiNode* add_child(aiNode* parent, const char* name, const aiMatrix4x4& transform) {
  aiNode* child = new aiNode(name);
  child->mTransformation = transform;
  child->mParent = parent;
  aiNode** children = new aiNode*[parent->mNumChildren + 1];
  for (unsigned i = 0; i < parent->mNumChildren; ++i) children[i] = parent->mChildren[i];
  children[parent->mNumChildren] = child;
  delete[] parent->mChildren;
  parent->mChildren = children;
  ++parent->mNumChildren;
  return child;
}

void attach_mesh(aiNode* node, unsigned mesh) {
  node->mNumMeshes = 1;
  node->mMeshes = new unsigned[1]{mesh};
}

/// A mesh of the given vertices and triangles (mesh space).
aiMesh* make_mesh(const char* name, const std::vector<aiVector3D>& vertices,
                  const std::vector<std::array<unsigned, 3>>& faces) {
  aiMesh* mesh = new aiMesh();
  mesh->mName = name;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = unsigned(vertices.size());
  mesh->mVertices = new aiVector3D[vertices.size()];
  std::copy(vertices.begin(), vertices.end(), mesh->mVertices);
  mesh->mNumFaces = unsigned(faces.size());
  mesh->mFaces = new aiFace[faces.size()];
  for (size_t f = 0; f < faces.size(); ++f) {
    mesh->mFaces[f].mNumIndices = 3;
    mesh->mFaces[f].mIndices = new unsigned[3]{faces[f][0], faces[f][1], faces[f][2]};
  }
  return mesh;
}

aiBone* make_bone(const char* name, const aiMatrix4x4& offset,
                  const std::vector<aiVertexWeight>& weights) {
  aiBone* bone = new aiBone();
  bone->mName = name;
  bone->mOffsetMatrix = offset;
  bone->mNumWeights = unsigned(weights.size());
  bone->mWeights = new aiVertexWeight[weights.size()];
  std::copy(weights.begin(), weights.end(), bone->mWeights);
  return bone;
}

/// An empty scene: a root node, one default material, room for meshes and one animation.
std::unique_ptr<aiScene> make_scene(std::vector<aiMesh*> meshes) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("root");
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial() };
  scene->mNumMeshes = unsigned(meshes.size());
  scene->mMeshes = new aiMesh*[meshes.size()];
  std::copy(meshes.begin(), meshes.end(), scene->mMeshes);
  return scene;
}

aiAnimation* add_animation(aiScene& scene, const char* name, double ticks_per_second) {
  aiAnimation* animation = new aiAnimation();
  animation->mName = name;
  animation->mTicksPerSecond = ticks_per_second;
  aiAnimation** animations = new aiAnimation*[scene.mNumAnimations + 1];
  for (unsigned i = 0; i < scene.mNumAnimations; ++i) animations[i] = scene.mAnimations[i];
  animations[scene.mNumAnimations] = animation;
  delete[] scene.mAnimations;
  scene.mAnimations = animations;
  ++scene.mNumAnimations;
  return animation;
}

aiNodeAnim* add_channel(aiAnimation& animation, const char* node) {
  aiNodeAnim* channel = new aiNodeAnim();
  channel->mNodeName = node;
  aiNodeAnim** channels = new aiNodeAnim*[animation.mNumChannels + 1];
  for (unsigned i = 0; i < animation.mNumChannels; ++i) channels[i] = animation.mChannels[i];
  channels[animation.mNumChannels] = channel;
  delete[] animation.mChannels;
  animation.mChannels = channels;
  ++animation.mNumChannels;
  return channel;
}

void set_rotation_keys(aiNodeAnim& channel,
                       const std::vector<std::pair<double, aiQuaternion>>& keys) {
  channel.mNumRotationKeys = unsigned(keys.size());
  channel.mRotationKeys = new aiQuatKey[keys.size()];
  for (size_t k = 0; k < keys.size(); ++k)
    channel.mRotationKeys[k] = aiQuatKey(keys[k].first, keys[k].second);
}

void set_position_keys(aiNodeAnim& channel,
                       const std::vector<std::pair<double, aiVector3D>>& keys) {
  channel.mNumPositionKeys = unsigned(keys.size());
  channel.mPositionKeys = new aiVectorKey[keys.size()];
  for (size_t k = 0; k < keys.size(); ++k)
    channel.mPositionKeys[k] = aiVectorKey(keys[k].first, keys[k].second);
}

aiQuaternion about_z(double degrees) {
  return aiQuaternion(aiVector3D(0, 0, 1), ai_real(degrees * M_PI / 180));
}

void expect_near(const Vec3& actual, const Vec3& expected, double tolerance = 1e-6) {
  EXPECT_LT((actual - expected).norm(), tolerance)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

// The skinned scene of the hand computation: a mesh node at (0, 0, 5), a bone node at (1, 0, 0)
// that turns 90 degrees about z over 10 ticks at 10 ticks per second, and a static anchor bone.
// Offset matrices map mesh space to bone space in the bind pose: O = inverse(G_bone) * G_mesh.
std::unique_ptr<aiScene> skinned_scene() {
  aiMesh* mesh =
      make_mesh("skin", {{2, 0, 0}, {2, 0, 1}, {1, 0, 0}, {0, 0, 0}}, {{0, 1, 2}, {0, 2, 3}});
  mesh->mNumBones = 2;
  mesh->mBones = new aiBone* [2] {
    make_bone("bone", translation(-1, 0, 5), {{0, 1.0f}, {1, 0.5f}, {2, 1.0f}}),
        make_bone("anchor", translation(0, 0, 5), {{1, 0.5f}}),
  };  // vertex 3 has no weights: it follows the mesh node rigidly
  auto scene = make_scene({mesh});
  attach_mesh(add_child(scene->mRootNode, "body", translation(0, 0, 5)), 0);
  add_child(scene->mRootNode, "bone", translation(1, 0, 0));
  add_child(scene->mRootNode, "anchor", aiMatrix4x4());
  aiAnimation* animation = add_animation(*scene, "bend", 10);
  set_rotation_keys(*add_channel(*animation, "bone"), {{0, about_z(0)}, {10, about_z(90)}});
  return scene;
}

TEST(ModelSkinning, BoneTurnedNinetyDegreesMovesVerticesAsComputedByHand) {
  const auto model = skinned_scene();
  const Scene scene = convert_model(*model, "skinned");
  scene.validate("skinned");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& object = scene.objects[0];
  ASSERT_EQ(object.key_times, (std::vector<double>{0.0, 1.0}));  // ticks 0 and 10 at 10 per second
  // Bind pose = mesh space moved by the mesh node (0, 0, 5).
  expect_near(object.key_positions[0][0], {2, 0, 5});
  expect_near(object.key_positions[0][1], {2, 0, 6});
  expect_near(object.key_positions[0][2], {1, 0, 5});
  expect_near(object.key_positions[0][3], {0, 0, 5});
  // t = 1 s: G_bone * O = T(1,0,0) Rz(90) T(-1,0,5). v0 = (2,0,0) -> (1,0,5) -> (0,1,5) -> (1,1,5).
  expect_near(object.key_positions[1][0], {1, 1, 5});
  // v1 = (2,0,1), half bone: (1,1,6); half anchor (bind pose): (2,0,6); blended (1.5, 0.5, 6).
  expect_near(object.key_positions[1][1], {1.5, 0.5, 6});
  // v2 sits on the bone's pivot; v3 has no bone and follows the mesh node.
  expect_near(object.key_positions[1][2], {1, 0, 5});
  expect_near(object.key_positions[1][3], {0, 0, 5});
  // Between keys the flightplan is the chord...
  expect_near(object.position(0, 0.5), {1.5, 0.5, 5});
  // ... and resampling at 4 keys per second puts a key on the arc: slerp to 45 degrees at 0.5 s.
  ModelOptions options;
  options.keyrate = 4;
  const Scene resampled = convert_model(*model, "skinned", options);
  ASSERT_EQ(resampled.objects[0].key_times, (std::vector<double>{0, 0.25, 0.5, 0.75, 1.0}));
  expect_near(resampled.objects[0].key_positions[2][0], {1 + std::sqrt(0.5), std::sqrt(0.5), 5});
  EXPECT_EQ(scene.time_begin, 0);
  EXPECT_EQ(scene.time_end, 1);
}

TEST(ModelSkinning, BoneWithoutNodeKeepsItsBindPose) {
  const auto model = skinned_scene();
  model->mMeshes[0]->mBones[0]->mName = "lost";  // "bone" no longer names a node
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = convert_model(*model, "lost-bone");
  EXPECT_NE(warnings.find("'lost'"), std::string::npos) << warnings;
  EXPECT_EQ(scene.objects[0].key_count(), 1u);  // nothing left that moves
  expect_near(scene.objects[0].key_positions[0][0], {2, 0, 5});
}

TEST(ModelSkinning, WeightsNotSummingToOneAreNormalized) {
  const auto model = skinned_scene();
  model->mMeshes[0]->mBones[1]->mWeights[0].mWeight = 1.5f;  // v1: 0.5 bone + 1.5 anchor
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = convert_model(*model, "unnormalized");
  EXPECT_NE(warnings.find("normalized"), std::string::npos) << warnings;
  // 1/4 of (1,1,6) + 3/4 of (2,0,6).
  expect_near(scene.objects[0].key_positions[1][1], {1.75, 0.25, 6});
}

TEST(ModelSkinning, MalformedWeightsAreInputErrors) {
  {
    const auto model = skinned_scene();
    model->mMeshes[0]->mBones[0]->mWeights[1].mVertexId = 4;  // the mesh has 4 vertices
    EXPECT_THROW((void)convert_model(*model, "oob"), InputError);
  }
  {
    const auto model = skinned_scene();
    model->mMeshes[0]->mBones[0]->mWeights[0].mWeight = std::nanf("");
    EXPECT_THROW((void)convert_model(*model, "nan"), InputError);
  }
  {
    const auto model = skinned_scene();
    model->mMeshes[0]->mBones[0]->mOffsetMatrix.a4 = INFINITY;
    EXPECT_THROW((void)convert_model(*model, "inf"), InputError);
  }
}

// A triangle (0,0,0), (1,0,0), (0,1,0) under a node at (10,0,0), with one morph target that lifts
// the top vertex by (0, 2, 0).
std::unique_ptr<aiScene> morph_scene(unsigned method, double default_weight) {
  aiMesh* mesh = make_mesh("blob", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  mesh->mMethod = method;
  aiAnimMesh* target = new aiAnimMesh();
  target->mNumVertices = 3;
  target->mVertices = new aiVector3D[3];
  const bool relative = method == aiMorphingMethod_MORPH_RELATIVE;
  for (unsigned v = 0; v < 3; ++v)
    target->mVertices[v] = relative ? aiVector3D(0, 0, 0) : mesh->mVertices[v];
  target->mVertices[2] += aiVector3D(0, 2, 0);
  target->mWeight = float(default_weight);
  mesh->mNumAnimMeshes = 1;
  mesh->mAnimMeshes = new aiAnimMesh* [1] { target };
  auto scene = make_scene({mesh});
  attach_mesh(add_child(scene->mRootNode, "blob_node", translation(10, 0, 0)), 0);
  return scene;
}

TEST(ModelMorph, TargetAtWeightHalfMovesTheVertexHalfway) {
  // assimp's usual absolute targets (glTF, FBX) and MORPH_RELATIVE displacements agree.
  for (unsigned method : {0u, unsigned(aiMorphingMethod_MORPH_NORMALIZED),
                          unsigned(aiMorphingMethod_MORPH_RELATIVE)}) {
    const auto model = morph_scene(method, 0.5);
    const Scene scene = convert_model(*model, "morph");
    ASSERT_EQ(scene.objects.size(), 1u);
    expect_near(scene.objects[0].key_positions[0][2],
                {10, 2, 0});  // (0,1,0) + 0.5 (0,2,0), then +(10,0,0)
    expect_near(scene.objects[0].key_positions[0][1], {11, 0, 0});
  }
}

TEST(ModelMorph, AnimatedWeightsComeFromTheMorphChannel) {
  const auto model = morph_scene(0, 0.5);
  aiAnimation* animation = add_animation(*model, "swell", 1);  // 1 tick per second
  aiMeshMorphAnim* channel = new aiMeshMorphAnim();
  channel->mName = "blob_node";  // glTF names the node
  channel->mNumKeys = 2;
  channel->mKeys = new aiMeshMorphKey[2];
  for (unsigned k = 0; k < 2; ++k) {
    channel->mKeys[k].mTime = 2.0 * k;
    channel->mKeys[k].mNumValuesAndWeights = 1;
    channel->mKeys[k].mValues = new unsigned[1]{0};
    channel->mKeys[k].mWeights = new double[1]{double(k)};
  }
  animation->mNumMorphMeshChannels = 1;
  animation->mMorphMeshChannels = new aiMeshMorphAnim* [1] { channel };
  const Scene scene = convert_model(*model, "swell");
  const Object& object = scene.objects.at(0);
  ASSERT_EQ(object.key_times, (std::vector<double>{0, 2}));
  expect_near(object.key_positions[0][2], {10, 1, 0});  // weight 0
  expect_near(object.key_positions[1][2], {10, 3, 0});  // weight 1
  expect_near(object.position(2, 1.0), {10, 2, 0});     // weight 0.5 halfway: linear in the weight
  EXPECT_EQ(scene.time_end, 2);

  channel->mKeys[1].mValues[0] = 1;  // the mesh has one target only
  EXPECT_THROW((void)convert_model(*model, "bad-target"), InputError);
}

/// Khronos' SimpleMorph: a triangle whose top vertex (0.5, 0.5, 0) has targets displaced by
/// (-1, 1, 0) and (1, 1, 0); the weights are keyed (0,0), (0,1), (1,1), (1,0), (0,0) at 0..4 s.
TEST(ModelMorph, SimpleMorphMatchesHandValues) {
  const std::filesystem::path path = kSharedModels / "glTF2/SimpleMorph/glTF/SimpleMorph.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not in the shared folder";
  const Scene scene = load_model(path.string());
  const Object& object = scene.objects.at(0);
  ASSERT_EQ(object.key_times, (std::vector<double>{0, 1, 2, 3, 4}));
  uint32_t top = 0;
  for (uint32_t v = 0; v < object.vertex_count(); ++v)
    if ((object.key_positions[0][v] - Vec3(0.5, 0.5, 0)).norm() < 1e-6) top = v;
  const std::vector<Vec3> expected = {
      {0.5, 0.5, 0}, {1.5, 1.5, 0}, {0.5, 2.5, 0}, {-0.5, 1.5, 0}, {0.5, 0.5, 0}};
  for (size_t k = 0; k < expected.size(); ++k)
    expect_near(object.key_positions[k][top], expected[k], 1e-6);
  expect_near(object.position(top, 1.5), {1.0, 2.0, 0}, 1e-6);  // weights (0.5, 1)
}

TEST(ModelAnimation, TracksInterpolateAndExtrapolateByState) {
  VectorTrack track;
  track.times = {10, 20};
  track.values = {Vec3(0, 0, 0), Vec3(10, 0, 0)};
  expect_near(sample(track, 15), {5, 0, 0});
  expect_near(sample(track, 5), {0, 0, 0});  // hold (CONSTANT, and assimp's DEFAULT)
  expect_near(sample(track, 25), {10, 0, 0});
  track.before = track.after = Extrapolation::linear;
  expect_near(sample(track, 5), {-5, 0, 0});
  expect_near(sample(track, 25), {15, 0, 0});
  track.before = track.after = Extrapolation::repeat;
  expect_near(sample(track, 5), {5, 0, 0});
  expect_near(sample(track, 27), {7, 0, 0});

  RotationTrack rotation;
  rotation.times = {0, 1};
  rotation.values = {Eigen::Quaterniond::Identity(),
                     Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()))};
  const Eigen::Quaterniond half = sample(rotation, 0.5);
  EXPECT_NEAR(half.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()))),
              0, kEps);
}

TEST(ModelAnimation, KeyTimesAreTheUnionOfEveryChannelsKeys) {
  const auto model = skinned_scene();
  aiNodeAnim* anchor = add_channel(*model->mAnimations[0], "anchor");
  set_position_keys(*anchor, {{0, {0, 0, 0}}, {5, {0, 1, 0}}, {10, {0, 0, 0}}});
  const Scene scene = convert_model(*model, "union");
  EXPECT_EQ(scene.objects[0].key_times, (std::vector<double>{0, 0.5, 1}));
  // At 0.5 s the bone is at 45 degrees and the anchor lifted by 1: v1 = half of each.
  const Vec3 bone_part(1 + std::sqrt(0.5), std::sqrt(0.5), 6), anchor_part(2, 1, 6);
  expect_near(scene.objects[0].key_positions[1][1], 0.5 * (bone_part + anchor_part));
}

TEST(ModelAnimation, UnsortedAndDuplicateKeysAreRepairedWithAWarning) {
  const auto model = skinned_scene();
  aiNodeAnim* anchor = add_channel(*model->mAnimations[0], "anchor");
  // Times 10, 0, 5, 5: sorted to 0, 5, 10; of the two keys at 5 the later one (y = 2) is kept.
  set_position_keys(*anchor, {{10, {0, 0, 0}}, {0, {0, 0, 0}}, {5, {0, 1, 0}}, {5, {0, 2, 0}}});
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = convert_model(*model, "unsorted");
  EXPECT_NE(warnings.find("not in time order"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("repeated"), std::string::npos) << warnings;
  EXPECT_EQ(scene.objects[0].key_times, (std::vector<double>{0, 0.5, 1}));
  // v1 is half anchor: at 0.5 s the anchor is lifted by 2, so v1.y = 0.5 * (sqrt(0.5) + 2).
  EXPECT_NEAR(scene.objects[0].key_positions[1][1].y(), 0.5 * (std::sqrt(0.5) + 2), 1e-6);
}

TEST(ModelAnimation, NanKeyTimesAndValuesAreInputErrors) {
  {
    const auto model = skinned_scene();
    model->mAnimations[0]->mChannels[0]->mRotationKeys[1].mTime = std::nan("");
    try {
      (void)convert_model(*model, "nan-time.x");
      FAIL() << "a NaN key time must be an InputError";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("nan-time.x"), std::string::npos);
      EXPECT_NE(std::string(error.what()).find("'bone'"), std::string::npos) << error.what();
    }
  }
  {
    const auto model = skinned_scene();
    model->mAnimations[0]->mChannels[0]->mRotationKeys[1].mValue = aiQuaternion(0, 0, 0, 0);
    EXPECT_THROW((void)convert_model(*model, "zero-rotation"), InputError);
  }
  {
    const auto model = skinned_scene();
    model->mAnimations[0]->mTicksPerSecond = -5;
    EXPECT_THROW((void)convert_model(*model, "negative-rate"), InputError);
  }
}

TEST(ModelAnimation, ZeroTicksPerSecondMeans25) {
  const auto model = skinned_scene();
  model->mAnimations[0]->mTicksPerSecond = 0;
  const Scene scene = convert_model(*model, "default-rate");
  EXPECT_EQ(scene.objects[0].key_times, (std::vector<double>{0, 10 / 25.0}));
}

TEST(ModelAnimation, SingleKeyAnimationIsAStillPoseForOneSecond) {
  const auto model = skinned_scene();
  aiNodeAnim* bone = model->mAnimations[0]->mChannels[0];
  bone->mNumRotationKeys = 1;  // only the key at tick 0 is left (aiScene still frees both)
  bone->mRotationKeys[0] = aiQuatKey(3, about_z(90));
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = convert_model(*model, "single-key");
  bone->mNumRotationKeys = 2;
  EXPECT_NE(warnings.find("single key time"), std::string::npos) << warnings;
  EXPECT_DOUBLE_EQ(scene.time_begin, 0.3);
  EXPECT_DOUBLE_EQ(scene.time_end, 1.3);
  EXPECT_EQ(scene.objects[0].key_count(), 1u);
  expect_near(scene.objects[0].key_positions[0][0], {1, 1, 5});  // posed at the key
}

TEST(ModelCamera, OwnCameraFollowsItsAnimatedNode) {
  const auto model = skinned_scene();
  aiNode* node = add_child(model->mRootNode, "eye", translation(0, 0, 20));
  (void)node;
  aiCamera* camera = new aiCamera();
  camera->mName = "eye";
  camera->mLookAt = aiVector3D(0, 0, -1);
  camera->mUp = aiVector3D(0, 1, 0);
  camera->mHorizontalFOV =
      ai_real(M_PI / 2);  // full horizontal angle, aspect 2: fov_y = 2 atan(0.5)
  camera->mAspect = 2;
  model->mNumCameras = 1;
  model->mCameras = new aiCamera* [1] { camera };
  set_position_keys(*add_channel(*model->mAnimations[0], "eye"),
                    {{0, {0, 0, 20}}, {10, {1, 0, 20}}});
  const Scene scene = convert_model(*model, "camera");
  ASSERT_EQ(scene.camera.keys.size(), 2u);
  expect_near(scene.camera.keys[0].position, {0, 0, 20});
  expect_near(scene.camera.keys[1].position, {1, 0, 20});
  EXPECT_NEAR(scene.camera.keys[1].time, 1.0, kEps);
  EXPECT_NEAR(scene.camera.keys[0].fov_y_degrees, 2 * std::atan(0.5) * 180 / M_PI,
              1e-5);  // float angle
  // It looks down world -z: the mesh (around z = 5) is straight ahead.
  EXPECT_GT(testing::fraction_in_view(scene, 0), 0.99);

  ModelOptions options;
  options.camera = ModelCamera::automatic;
  const Scene framed = convert_model(*model, "camera", options);
  EXPECT_EQ(framed.camera.keys.size(), 1u);
  EXPECT_TRUE(testing::bounds_in_view(framed, 0));
}

TEST(ModelCamera, AutomaticFramingLooksAtTheCentreFromAboveAndInFront) {
  const auto model = skinned_scene();
  const Scene scene = convert_model(*model, "framing");
  ASSERT_EQ(scene.camera.keys.size(), 1u);
  const CameraKey& key = scene.camera.keys[0];
  EXPECT_EQ(key.fov_y_degrees, 45);
  const Vec3 centre = scene.bounds().center();
  const Vec3 centre_seen = testing::to_camera(scene, centre, 0);
  EXPECT_NEAR(centre_seen.x(), 0, 1e-9);
  EXPECT_NEAR(centre_seen.y(), 0, 1e-9);
  EXPECT_GT(key.position.z(), centre.z());  // in front
  EXPECT_GT(key.position.y(), centre.y());  // above
  for (double t : {0.0, 0.5, 1.0}) EXPECT_DOUBLE_EQ(testing::fraction_in_view(scene, t), 1.0);
  EXPECT_TRUE(testing::bounds_in_view(scene, 0));
}

}  // namespace
}  // namespace kinray
